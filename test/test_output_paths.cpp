// A run's outputs checked against its inputs and each other before any work: the same file by
// another name, a file inside an input folder, folders that do not exist, are files or are
// read-only, two outputs on one file; and what must pass (new files, new nested folders).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "strata/core/error.h"
#include "strata/core/output_paths.h"
#include "test_utils.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

class OutputPathsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::freshTempDir("output_paths");
    fs::create_directories(dir_ / "session" / "mav0" / "imu0");
    std::ofstream(dir_ / "session" / "mav0" / "imu0" / "data.csv") << "1,2,3\n";
    std::ofstream(dir_ / "truth.txt") << "0 0 0 0 0 0 0 1\n";
  }
  void TearDown() override {
    ::chmod((dir_ / "locked").c_str(), 0755);
    fs::remove_all(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  /// The message check() throws, "" when it passes.
  static std::string problem(const OutputPaths& paths) {
    try {
      paths.check();
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

TEST_F(OutputPathsTest, NewFilesAndNewNestedFoldersPass) {
  OutputPaths paths;
  paths.inputFolder(path("session"), "the session");
  paths.inputFile(path("truth.txt"), "the truth");
  paths.outputFile(path("trajectory.txt"), "--out");
  paths.outputFile(path("session/summary.json"), "--summary");  // new, beside the inputs
  paths.outputFolder(path("runs/a/b"), "--out-dir");
  paths.outputFile("", "--plot");  // not given
  EXPECT_EQ(problem(paths), "");
}

TEST_F(OutputPathsTest, AnOutputOnAnInputFileIsRefusedByAnyName) {
  OutputPaths paths;
  paths.inputFile(path("truth.txt"), "GROUND_TRUTH");
  paths.outputFile(path("session/../truth.txt"), "--json");
  const std::string message = problem(paths);
  EXPECT_NE(message.find("--json"), std::string::npos) << message;
  EXPECT_NE(message.find("GROUND_TRUTH"), std::string::npos) << message;

  fs::create_symlink(dir_ / "truth.txt", dir_ / "link.txt");
  OutputPaths linked;
  linked.inputFile(path("link.txt"), "GROUND_TRUTH");
  linked.outputFile(path("truth.txt"), "--json");
  EXPECT_NE(problem(linked), "");
}

TEST_F(OutputPathsTest, AnOutputOnAFileInsideAnInputFolderIsRefused) {
  OutputPaths paths;
  paths.inputFolder(path("session"), "the session");
  paths.outputFile(path("session/mav0/imu0/data.csv"), "--out");
  const std::string message = problem(paths);
  EXPECT_NE(message.find("would overwrite a file of the input"), std::string::npos) << message;
}

TEST_F(OutputPathsTest, AnOutputFolderThatIsAnInputFolderIsRefused) {
  OutputPaths paths;
  paths.inputFolder(path("session"), "SESSION");
  paths.outputFolder(path("session/mav0/.."), "--out");
  EXPECT_NE(problem(paths).find("same folder"), std::string::npos);
}

TEST_F(OutputPathsTest, TwoOutputsOnOneFileAreRefused) {
  OutputPaths paths;
  paths.outputFile(path("trajectory.txt"), "--out");
  paths.outputFile(path("./trajectory.txt"), "--summary");
  const std::string message = problem(paths);
  EXPECT_NE(message.find("--summary"), std::string::npos) << message;
  EXPECT_NE(message.find("--out"), std::string::npos) << message;
}

TEST_F(OutputPathsTest, MissingFolderFileAsFolderAndFolderAsFileAreRefused) {
  OutputPaths missing;
  missing.outputFile(path("no/such/folder/trajectory.txt"), "--out");
  EXPECT_NE(problem(missing).find("does not exist"), std::string::npos);

  OutputPaths file_as_folder;
  file_as_folder.outputFolder(path("truth.txt/runs"), "--out-dir");
  EXPECT_NE(problem(file_as_folder).find("is not a folder"), std::string::npos);

  OutputPaths folder_as_file;
  folder_as_file.outputFile(path("session"), "--map");
  EXPECT_NE(problem(folder_as_file).find("is a folder"), std::string::npos);
}

TEST_F(OutputPathsTest, ReadOnlyFolderIsRefusedBeforeAnyWork) {
  if (::geteuid() == 0) GTEST_SKIP() << "root writes into read-only folders; nothing to check";
  fs::create_directories(dir_ / "locked");
  ::chmod((dir_ / "locked").c_str(), 0555);
  OutputPaths file;
  file.outputFile(path("locked/map.strata"), "--map");
  EXPECT_NE(problem(file).find("not writable"), std::string::npos);
  OutputPaths folder;
  folder.outputFolder(path("locked/new"), "--out");
  EXPECT_NE(problem(folder).find("not writable"), std::string::npos);
}

}  // namespace
}  // namespace strata
