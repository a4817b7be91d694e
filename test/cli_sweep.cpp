#include "cli_sweep.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "test_utils.h"

namespace strata::test {

namespace fs = std::filesystem;

std::map<std::string, std::string> snapshotTree(const fs::path& root) {
  std::map<std::string, std::string> entries;
  if (fs::is_regular_file(root)) {
    entries[root.string()] = readText(root);
    return entries;
  }
  if (!fs::is_directory(root)) return entries;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(root)) {
    if (e.is_directory()) {
      entries[e.path().string()] = "<folder>";
    } else if (e.is_regular_file()) {
      entries[e.path().string()] = readText(e.path());
    } else {
      entries[e.path().string()] = "<other>";
    }
  }
  return entries;
}

std::string treeDifferences(const std::map<std::string, std::string>& before,
                            const std::map<std::string, std::string>& after) {
  std::ostringstream s;
  for (const auto& [path, bytes] : before) {
    const auto it = after.find(path);
    if (it == after.end()) {
      s << " removed " << path << ";";
    } else if (it->second != bytes) {
      s << " changed " << path << ";";
    }
  }
  for (const auto& [path, bytes] : after) {
    if (before.count(path) == 0) s << " added " << path << ";";
  }
  return s.str();
}

void writeText(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

void makeCommonFixtures(const fs::path& dir) {
  writeText(dir / "a_file", "a file, not a folder\n");
  fs::create_directories(dir / "a_folder");
  fs::create_directories(dir / "readonly");
  fs::permissions(dir / "readonly", fs::perms::owner_read | fs::perms::owner_exec |
                                        fs::perms::group_read | fs::perms::group_exec |
                                        fs::perms::others_read | fs::perms::others_exec);
}

void removeFixtures(const fs::path& dir) {
  std::error_code error;
  fs::permissions(dir / "readonly", fs::perms::owner_all, fs::perm_options::add, error);
  fs::remove_all(dir, error);
}

std::size_t sweepRows(const std::string& command, const std::vector<SweepRow>& rows,
                      const fs::path& fixture, double max_seconds) {
  const bool read_only_folders_work = ::geteuid() != 0;
  std::size_t run = 0;
  for (const SweepRow& row : rows) {
    SCOPED_TRACE(command + ": " + row.what);
    if (row.needs_read_only_folder && !read_only_folders_work) {
      std::printf("[ skipped  ] %s: %s (a read-only folder is writable as root)\n",
                  command.c_str(), row.what.c_str());
      continue;
    }
    std::map<std::string, std::map<std::string, std::string>> inputs;
    for (const fs::path& p : row.unchanged) {
      EXPECT_TRUE(fs::exists(p)) << "the row's input " << p << " must exist";
      inputs[p.string()] = snapshotTree(p);
    }
    for (const fs::path& p : row.absent) EXPECT_FALSE(fs::exists(p)) << p << " exists before";
    const auto whole = snapshotTree(fixture);
    testing::internal::CaptureStdout();
    testing::internal::CaptureStderr();
    const auto start = std::chrono::steady_clock::now();
    const int code = row.run();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::string out = testing::internal::GetCapturedStdout();
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(code, row.exit_code) << "stderr: " << err << "\nstdout: " << out;
    for (const std::string& word : row.words) {
      EXPECT_NE(err.find(word), std::string::npos) << "'" << word << "' is not in: " << err;
    }
    for (const fs::path& p : row.unchanged) {
      EXPECT_EQ(treeDifferences(inputs[p.string()], snapshotTree(p)), "") << "input " << p;
    }
    for (const fs::path& p : row.absent) EXPECT_FALSE(fs::exists(p)) << "output " << p;
    EXPECT_EQ(treeDifferences(whole, snapshotTree(fixture)), "") << "the run left files behind";
    EXPECT_LT(seconds, max_seconds) << "bad input must be refused before the work";
    ++run;
  }
  std::printf("strata %s: %zu bad runs swept\n", command.c_str(), run);
  return run;
}

}  // namespace strata::test
