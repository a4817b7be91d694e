// The solver's own log (glog, as Ceres writes it) stays out of stderr unless asked for, is
// counted with its first message kept, and writes no log files.
#include <glog/logging.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "strata/odometry/solver_log.h"

namespace strata::odometry {
namespace {

std::size_t glogFilesIn(const std::filesystem::path& dir) {
  std::size_t n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().filename().string().find(".log.") != std::string::npos) ++n;
  }
  return n;
}

TEST(SolverLog, KeepsTheSolversLinesOffStderrUnlessAskedAndCountsThem) {
  const std::filesystem::path tmp = std::filesystem::temp_directory_path();
  const std::size_t files_before = glogFilesIn(tmp);
  SolverLog& log = SolverLog::install("test_solver_log", false);
  EXPECT_EQ(log.messages(), 0u);
  EXPECT_EQ(log.summary(), "");

  testing::internal::CaptureStderr();
  LOG(WARNING) << "Error in evaluating the ResidualBlock.";
  LOG(ERROR) << "a second line";
  const std::string quiet = testing::internal::GetCapturedStderr();
  EXPECT_EQ(quiet, "") << "the solver's lines reached stderr";
  EXPECT_EQ(log.messages(), 2u);
  EXPECT_NE(log.first().find("Error in evaluating the ResidualBlock."), std::string::npos)
      << log.first();
  EXPECT_NE(log.summary().find("the solver logged 2 messages"), std::string::npos) << log.summary();

  SolverLog::install("test_solver_log", true);  // --solver-log
  testing::internal::CaptureStderr();
  LOG(WARNING) << "shown when asked for";
  const std::string shown = testing::internal::GetCapturedStderr();
  EXPECT_NE(shown.find("shown when asked for"), std::string::npos) << shown;
  EXPECT_EQ(log.messages(), 3u);
  EXPECT_EQ(glogFilesIn(tmp), files_before) << "glog wrote log files";
}

}  // namespace
}  // namespace strata::odometry
