#pragma once
// JSON text helpers shared by every report writer (ground truth, demo, diff).
#include <string>

namespace strata {

/// `text` as a JSON string literal: quotes, backslashes and control characters escaped.
std::string jsonQuoted(const std::string& text);

}  // namespace strata
