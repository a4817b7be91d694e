#pragma once
// What a run of a command writes, for the commands that write a folder of files:
// outputFolderFiles() registers the folder and its fixed files with OutputPaths (core/
// output_paths.h) for the check before any work, and OutputCleanup undoes what a failed run
// created: a folder that did not exist (with everything in it), the files it added to a folder
// that did, single files that did not exist. What existed before the run is never touched (files
// are written atomically, so one the run replaced is whole, old or new).
// Thread safety: not thread safe (one per run).
#include <filesystem>
#include <set>
#include <string>
#include <system_error>
#include <vector>

#include "strata/core/output_paths.h"

namespace strata::apps {

/// Registers `folder` as an output folder (`role`: its option) and, when it exists, each of
/// `files` in it as an output file, so that one of them that is an input or a folder is refused.
/// A new folder holds nothing yet: its files can collide with nothing.
inline void outputFolderFiles(OutputPaths& paths, const std::string& folder,
                              const std::string& role, const std::vector<std::string>& files) {
  paths.outputFolder(folder, role);
  std::error_code error;
  if (folder.empty() || !std::filesystem::is_directory(folder, error)) return;
  for (const std::string& name : files) {
    paths.outputFile((std::filesystem::path(folder) / name).string(), role);
  }
}

class OutputCleanup {
 public:
  OutputCleanup() = default;
  OutputCleanup(const OutputCleanup&) = delete;
  OutputCleanup& operator=(const OutputCleanup&) = delete;
  /// Undoes what the run created unless keep() was called.
  ~OutputCleanup() {
    if (!kept_) undo();
  }

  /// Before the run creates or writes into `folder`: when it does not exist, a failure removes
  /// the outermost of its folders that did not exist; when it does, a failure removes the entries
  /// the run added to it whose names match `names` ("report.json", or a prefix: "session_*").
  void folder(const std::string& path, const std::vector<std::string>& names) {
    namespace fs = std::filesystem;
    if (path.empty()) return;
    std::error_code error;
    fs::path absolute = fs::absolute(path, error).lexically_normal();
    if (error) return;
    if (absolute.filename().empty()) absolute = absolute.parent_path();  // "out/"
    const bool exists = fs::exists(absolute, error);
    if (error) return;  // cannot tell (no permission): touch nothing
    if (!exists) {
      fs::path outermost = absolute;
      while (outermost.has_parent_path() && outermost.parent_path() != outermost) {
        const bool parent_exists = fs::exists(outermost.parent_path(), error);
        if (error) return;
        if (parent_exists) break;
        outermost = outermost.parent_path();
      }
      created_folders_.push_back(outermost);
      return;
    }
    Folder known{absolute, names, {}};
    for (fs::directory_iterator it(absolute, error), end; !error && it != end;
         it.increment(error)) {
      known.before.insert(it->path().filename().string());
    }
    folders_.push_back(std::move(known));
  }

  /// Before the run writes `path`: a failure removes it when it did not exist.
  void file(const std::string& path) {
    std::error_code error;
    if (path.empty()) return;
    const bool exists = std::filesystem::exists(path, error);
    if (!error && !exists) new_files_.push_back(path);
  }

  /// The run succeeded: keep everything.
  void keep() { kept_ = true; }

 private:
  struct Folder {
    std::filesystem::path path;
    std::vector<std::string> names;
    std::set<std::string> before;
  };

  static bool matches(const std::string& name, const std::vector<std::string>& patterns) {
    for (const std::string& p : patterns) {
      if (!p.empty() && p.back() == '*') {
        if (name.compare(0, p.size() - 1, p, 0, p.size() - 1) == 0) return true;
      } else if (name == p) {
        return true;
      }
    }
    return false;
  }

  void undo() noexcept {
    namespace fs = std::filesystem;
    std::error_code ignored;
    for (const std::string& f : new_files_) fs::remove(f, ignored);
    for (const Folder& folder : folders_) {
      std::vector<fs::path> added;
      for (fs::directory_iterator it(folder.path, ignored), end; !ignored && it != end;
           it.increment(ignored)) {
        const std::string name = it->path().filename().string();
        if (folder.before.count(name) == 0 && matches(name, folder.names)) {
          added.push_back(it->path());
        }
      }
      ignored.clear();
      for (const fs::path& p : added) fs::remove_all(p, ignored);
    }
    for (const fs::path& f : created_folders_) fs::remove_all(f, ignored);
  }

  bool kept_ = false;
  std::vector<std::filesystem::path> created_folders_;
  std::vector<Folder> folders_;
  std::vector<std::string> new_files_;
};

}  // namespace strata::apps
