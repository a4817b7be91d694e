#pragma once
// The files and folders one run of a program reads and writes, checked together before any work:
// every output can be written where it is asked for (its folder exists and is writable, it is not
// a folder itself, an output folder is a folder or can be made in a writable one), no output is
// one of the inputs or lies on a file inside an input folder, and no two outputs are one file.
// Paths are compared as files where both exist (same device and inode: links, "..", bind mounts)
// and as normalised absolute paths otherwise.
// Errors: check() throws InputError naming the output, the option or role it came from, and the
// input or other output it collides with. Nothing is created or written by this class.
// Thread safety: not thread safe (one per run).
#include <string>
#include <vector>

namespace strata {

class OutputPaths {
 public:
  /// A file the run reads (`role` names it in messages: "--truth", "the IMU file", ...).
  /// Empty paths are ignored (an optional input not given).
  void inputFile(const std::string& path, const std::string& role);
  /// A folder the run reads from: no output may be the folder itself or an existing file in it
  /// (at any depth); new files beside its own are allowed.
  void inputFolder(const std::string& path, const std::string& role);
  /// A file the run writes (atomically, so its folder must be writable). Empty paths are ignored.
  void outputFile(const std::string& path, const std::string& role);
  /// A folder the run writes into: an existing writable folder, or a new one whose nearest
  /// existing ancestor is a writable folder. Empty paths are ignored.
  void outputFolder(const std::string& path, const std::string& role);

  /// Throws InputError naming the first problem found; returns when every output can be written
  /// and none collides with an input or another output.
  void check() const;

 private:
  struct Entry {
    std::string path;
    std::string role;
  };
  std::vector<Entry> input_files_, input_folders_, output_files_, output_folders_;
};

}  // namespace strata
