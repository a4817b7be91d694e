#pragma once
// JSON text helpers shared by every report writer (ground truth, demo, diff).
#include <string>

namespace strata {

/// `text` as a JSON string literal: quotes, backslashes and control characters escaped.
std::string jsonQuoted(const std::string& text);

/// `v` as a JSON number with 9 significant digits; NaN and infinities as null.
std::string jsonNumber(double v);

}  // namespace strata
