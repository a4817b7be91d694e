#pragma once
// Shared test helpers: where the shared test data lives, and skipping cleanly when it is absent.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace strata::test {

/// ../shared/data beside the project (or $STRATA_DATA_DIR), "" when it does not exist.
std::string sharedDataDir();

/// Path of a folder/file inside the shared data, "" when absent.
std::string sharedDataPath(const std::string& relative);

/// An empty folder strata_test_<name>_<pid> in the temporary directory (emptied when it exists;
/// the process id keeps two test runs on one machine apart).
std::filesystem::path freshTempDir(const std::string& name);

/// The whole file as text ("" when it cannot be read).
std::string readText(const std::filesystem::path& path);

}  // namespace strata::test

/// Skips the current test with a message naming the missing data when it is absent.
#define STRATA_REQUIRE_DATA(relative, out_path)                                        \
  const std::string out_path = ::strata::test::sharedDataPath(relative);               \
  if (out_path.empty()) {                                                              \
    GTEST_SKIP() << "test data '" << (relative) << "' not found under ../shared/data " \
                 << "(set STRATA_DATA_DIR to its folder); skipping";                   \
  }
