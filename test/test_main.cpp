// Test entry point: fails any test during which the Vulkan validation layer reported an error.
#include <gtest/gtest.h>

#include <cstdlib>
#include <sstream>

#include "strata/vk/vk.h"

namespace {

class ValidationErrorListener : public testing::EmptyTestEventListener {
 public:
  void OnTestStart(const testing::TestInfo&) override {
    errors_at_start_ = strata::vk::validationErrorCount();
    strata::vk::takeValidationMessages();
  }
  void OnTestEnd(const testing::TestInfo& info) override {
    const std::uint64_t new_errors = strata::vk::validationErrorCount() - errors_at_start_;
    if (new_errors == 0) return;
    std::ostringstream msg;
    msg << new_errors << " Vulkan validation error(s) during " << info.test_suite_name() << "."
        << info.name() << ":";
    for (const std::string& m : strata::vk::takeValidationMessages()) msg << "\n  " << m;
    ADD_FAILURE() << msg.str();
  }

 private:
  std::uint64_t errors_at_start_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  // ctest runs two tests at once: two lavapipe threads each (unless the caller chose). Set here,
  // not in CMake: gtest_discover_tests passes only the first variable of an ENVIRONMENT list.
  setenv("LP_NUM_THREADS", "2", 0);
  testing::InitGoogleTest(&argc, argv);
  // Appended after the default printer so the failure is attributed to the test that caused it.
  testing::UnitTest::GetInstance()->listeners().Append(new ValidationErrorListener);
  return RUN_ALL_TESTS();
}
