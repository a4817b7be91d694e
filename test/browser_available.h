#pragma once
// Whether the browser tests can run here: Debian's Chromium (or STRATA_CHROMIUM), Node.js and
// web/'s playwright-core (STRATA_WEB_DIR, the including test's compile definition). "" when they
// can, else what is missing, for GTEST_SKIP.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace strata::test {

inline std::string chromiumPath() {
  const char* env = std::getenv("STRATA_CHROMIUM");
  return env ? env : "/usr/bin/chromium";
}

inline std::string browserUnavailable() {
  if (access(chromiumPath().c_str(), X_OK) != 0) return "no Chromium at " + chromiumPath() + " (apt-get install chromium)";
  if (std::system("node --version > /dev/null 2>&1") != 0) return "no Node.js (node) on PATH";
  if (!std::filesystem::exists(std::filesystem::path(STRATA_WEB_DIR) / "node_modules" / "playwright-core")) {
    return "web/node_modules has no playwright-core (npm ci in web/)";
  }
  return "";
}

}  // namespace strata::test
