#pragma once
// The bad-input sweeps of the programs: tables of runs that must be refused before any work, each
// checked for its exit code, the words of its message, inputs byte for byte as they were, outputs
// that must not exist, and nothing changed in the fixture's folder.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace strata::test {

/// One bad run: what it is, the run (a command's runX on its options), the exit code, words its
/// message (stderr) must hold, inputs (files or folders) that must stay byte for byte as they
/// were, outputs that must not exist before or after, and whether it needs a read-only folder
/// (skipped where one is writable: as root).
struct SweepRow {
  std::string what;
  std::function<int()> run;
  int exit_code = 2;
  std::vector<std::string> words;
  std::vector<std::filesystem::path> unchanged;
  std::vector<std::filesystem::path> absent;
  bool needs_read_only_folder = false;
};

/// Writes `text` to `path`, making its folders (fixture files).
void writeText(const std::filesystem::path& path, const std::string& text);

/// The fixtures every sweep needs, in `dir`: `a_file` (a file where a folder is expected),
/// `a_folder` (a folder where a file is expected) and `readonly` (a folder without write
/// permission: writable anyway as root, where the rows needing it skip).
void makeCommonFixtures(const std::filesystem::path& dir);
/// Undoes makeCommonFixtures' permissions and removes `dir` (for TearDown; never throws).
void removeFixtures(const std::filesystem::path& dir);

/// Every file (its bytes) and folder under `root` (or `root` itself when it is a file), by path.
std::map<std::string, std::string> snapshotTree(const std::filesystem::path& root);

/// The paths added, removed or changed between two snapshots ("" when none).
std::string treeDifferences(const std::map<std::string, std::string>& before,
                            const std::map<std::string, std::string>& after);

/// Runs every row (GoogleTest failures name `command` and the row), each also checked to leave
/// `fixture` (the folder of the rows' inputs) unchanged and to finish within `max_seconds`: bad
/// input is refused before the work. Returns the number of rows run (skipped ones not counted).
std::size_t sweepRows(const std::string& command, const std::vector<SweepRow>& rows,
                      const std::filesystem::path& fixture, double max_seconds = 10.0);

}  // namespace strata::test
