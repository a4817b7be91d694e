#include "strata/core/output_paths.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <system_error>

#include "strata/core/error.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

/// `path` absolute, with "." and ".." resolved as far as it exists (links followed there).
fs::path normalised(const std::string& path) {
  std::error_code error;
  const fs::path absolute = fs::absolute(path, error);
  if (error) return fs::path(path).lexically_normal();
  const fs::path resolved = fs::weakly_canonical(absolute, error);
  return error ? absolute.lexically_normal() : resolved;
}

bool pathExists(const fs::path& path) {
  std::error_code error;
  return fs::exists(path, error);
}

bool isFolderPath(const fs::path& path) {
  std::error_code error;
  return fs::is_directory(path, error);
}

bool sameFile(const std::string& a, const std::string& b) {
  std::error_code error;
  if (pathExists(a) && pathExists(b)) return fs::equivalent(a, b, error) && !error;
  return normalised(a) == normalised(b);
}

/// Whether `file` exists inside `folder` (at any depth).
bool existsInside(const std::string& file, const std::string& folder) {
  if (!pathExists(file) || !isFolderPath(folder)) return false;
  const fs::path f = normalised(file), d = normalised(folder);
  const auto mismatch = std::mismatch(d.begin(), d.end(), f.begin(), f.end());
  return mismatch.first == d.end() && mismatch.second != f.end();
}

std::string quoted(const std::string& role, const std::string& path) {
  return role + " '" + path + "'";
}

void requireWritableFolder(const fs::path& folder, const std::string& what) {
  if (!pathExists(folder)) {
    throw InputError(what + ": the folder '" + folder.string() + "' does not exist");
  }
  if (!isFolderPath(folder)) throw InputError(what + ": '" + folder.string() + "' is not a folder");
  if (::access(folder.c_str(), W_OK | X_OK) != 0) {
    throw InputError(what + ": the folder '" + folder.string() + "' is not writable");
  }
}

void checkWritableFile(const std::string& path, const std::string& role) {
  const std::string what = quoted(role, path);
  if (isFolderPath(path)) throw InputError(what + " is a folder, not a file");
  fs::path parent = normalised(path).parent_path();
  if (parent.empty()) parent = ".";
  requireWritableFolder(parent, what);
}

void checkWritableFolder(const std::string& path, const std::string& role) {
  const std::string what = quoted(role, path);
  if (pathExists(path)) {
    requireWritableFolder(normalised(path), what);
    return;
  }
  fs::path ancestor = normalised(path).parent_path();
  while (!ancestor.empty() && !pathExists(ancestor) && ancestor != ancestor.root_path())
    ancestor = ancestor.parent_path();
  if (ancestor.empty()) ancestor = ".";
  requireWritableFolder(ancestor, what);
}

}  // namespace

void OutputPaths::inputFile(const std::string& path, const std::string& role) {
  if (!path.empty()) input_files_.push_back({path, role});
}

void OutputPaths::inputFolder(const std::string& path, const std::string& role) {
  if (!path.empty()) input_folders_.push_back({path, role});
}

void OutputPaths::outputFile(const std::string& path, const std::string& role) {
  if (!path.empty()) output_files_.push_back({path, role});
}

void OutputPaths::outputFolder(const std::string& path, const std::string& role) {
  if (!path.empty()) output_folders_.push_back({path, role});
}

void OutputPaths::check() const {
  for (const Entry& out : output_files_) checkWritableFile(out.path, out.role);
  for (const Entry& out : output_folders_) checkWritableFolder(out.path, out.role);
  const auto collide = [](const Entry& out, const Entry& other, const char* relation) {
    throw InputError(quoted(out.role, out.path) + " " + relation + " " +
                     quoted(other.role, other.path) + ": choose another path");
  };
  for (const Entry& out : output_files_) {
    for (const Entry& in : input_files_)
      if (sameFile(out.path, in.path)) collide(out, in, "is the same file as the input");
    for (const Entry& in : input_folders_)
      if (existsInside(out.path, in.path)) collide(out, in, "would overwrite a file of the input");
  }
  for (const Entry& out : output_folders_) {
    for (const Entry& in : input_folders_)
      if (sameFile(out.path, in.path)) collide(out, in, "is the same folder as the input");
    for (const Entry& in : input_files_)
      if (sameFile(out.path, in.path)) collide(out, in, "is the input");
  }
  for (std::size_t i = 0; i < output_files_.size(); ++i) {
    for (std::size_t j = i + 1; j < output_files_.size(); ++j) {
      if (sameFile(output_files_[i].path, output_files_[j].path))
        collide(output_files_[j], output_files_[i], "is the same file as the output");
    }
    for (const Entry& folder : output_folders_) {
      if (sameFile(output_files_[i].path, folder.path))
        collide(output_files_[i], folder, "is the output folder");
    }
  }
}

}  // namespace strata
