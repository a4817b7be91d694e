// Saving a map (or a mesh: the same atomic writer) when the file system fails: a full disk, a
// failed flush or rename, a read-only folder. Each fault comes injected at the system call
// (FileFaultInjection, always runs) and, where the test may mount file systems (root, no container
// restriction), for real on a small or read-only tmpfs. Either way: an error naming the path and
// the system's reason, the previous file byte for byte as it was, and no temporary file left
// behind.
#include <gtest/gtest.h>
#include <sys/mount.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <string>

#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/core/file_faults.h"
#include "strata/map/map_file.h"
#include "strata/mesh/extract_mesh.h"
#include "strata/mesh/ply.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

/// A map of `blocks` blocks in a row, every voxel observed (about 6 KiB a block on disk).
TsdfMap mapOfBlocks(int blocks) {
  TsdfMap map{MapConfig{}};
  for (int b = 0; b < blocks; ++b) {
    TsdfBlock& block = map.allocateBlock(BlockIndex(b, 0, 0));
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      block[i] = TsdfVoxel{0.001f * static_cast<float>(i - 256), 1.0f + b,
                           packRgb(static_cast<std::uint8_t>(b), 2, 3)};
    }
  }
  return map;
}

/// Files in `dir` other than `keep` (a temporary left behind would be one).
std::vector<std::string> strayFiles(const fs::path& dir, const fs::path& keep) {
  std::vector<std::string> stray;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    if (entry.path() != keep) stray.push_back(entry.path().filename().string());
  }
  return stray;
}

/// Saves `map` to `path` expecting an Error; returns its message.
std::string failedSave(const TsdfMap& map, const fs::path& path) {
  try {
    saveMap(map, path.string());
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "saving '" << path.string() << "' should have failed";
  return "";
}

/// Descriptors open in this process (a failed save must close its temporary).
std::size_t openDescriptors() {
  const fs::directory_iterator fds("/proc/self/fd");
  return static_cast<std::size_t>(std::distance(fs::begin(fds), fs::end(fds)));
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// A tmpfs mounted on a fresh folder for the test's lifetime; ok() is false where mounting is not
/// allowed (why() says why), and the test skips.
class ScopedTmpfs {
 public:
  ScopedTmpfs(const fs::path& dir, const std::string& options) : dir_(dir) {
    fs::create_directories(dir_);
    mounted_ = ::mount("tmpfs", dir_.c_str(), "tmpfs", 0, options.c_str()) == 0;
    if (!mounted_) why_ = std::strerror(errno);
  }
  ~ScopedTmpfs() {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
  }
  ScopedTmpfs(const ScopedTmpfs&) = delete;
  ScopedTmpfs& operator=(const ScopedTmpfs&) = delete;

  bool ok() const { return mounted_; }
  const std::string& why() const { return why_; }
  /// Read-only from now on (MS_REMOUNT | MS_RDONLY): even root cannot write.
  bool makeReadOnly() {
    return ::mount(nullptr, dir_.c_str(), nullptr, MS_REMOUNT | MS_RDONLY, nullptr) == 0;
  }

 private:
  fs::path dir_;
  bool mounted_ = false;
  std::string why_;
};

#define STRATA_REQUIRE_MOUNT(tmpfs)                                                           \
  if (!(tmpfs).ok()) {                                                                        \
    GTEST_SKIP() << "cannot mount a tmpfs here (" << (tmpfs).why()                            \
                 << "; needs root outside a restricted container); the injected variant ran"; \
  }

class FileFaults : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("strata_file_faults_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    FileFaultInjection::disarm();
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }

  /// Saves the small map at `path` (the previous file) and returns its bytes.
  std::vector<std::uint8_t> savePrevious(const fs::path& path) {
    saveMap(small_, path.string());
    return readFile(path.string());
  }

  /// The guarantees after a failed save over `path`: the previous bytes, no temporary beside.
  void expectPreviousKept(const fs::path& path, const std::vector<std::uint8_t>& previous) {
    EXPECT_EQ(readFile(path.string()), previous) << "'" << path.string() << "' changed";
    EXPECT_EQ(strayFiles(path.parent_path(), path), std::vector<std::string>{})
        << "a temporary was left behind";
  }

  /// Injects `error_number` at `step`, saves the big map over the previous file; returns the
  /// error after checking the guarantees and that the message names the path and the reason.
  std::string injectedFailure(FileStep step, int error_number) {
    const fs::path path = dir_ / "map.strata";
    const std::vector<std::uint8_t> previous = savePrevious(path);
    const std::size_t descriptors = openDescriptors();
    const ScopedFileFault fault(step, error_number);
    const std::string error = failedSave(big_, path);
    EXPECT_EQ(openDescriptors(), descriptors) << "the failed save leaked a file descriptor";
    EXPECT_TRUE(contains(error, path.string())) << error;
    EXPECT_TRUE(contains(error, std::strerror(error_number))) << error;
    expectPreviousKept(path, previous);
    return error;
  }

  fs::path dir_;
  const TsdfMap small_ = mapOfBlocks(2);  // ~12 KiB
  const TsdfMap big_ = mapOfBlocks(20);   // ~120 KiB: more than the 64 KiB tmpfs holds
};

TEST_F(FileFaults, InjectedFullDiskKeepsThePreviousFile) {
  const std::string error = injectedFailure(FileStep::kWrite, ENOSPC);
  EXPECT_TRUE(contains(error, "No space left on device")) << error;
  // The fault was one write: the next save goes through.
  saveMap(big_, (dir_ / "map.strata").string());
  EXPECT_EQ(loadMap((dir_ / "map.strata").string()).blockCount(), big_.blockCount());
}

TEST_F(FileFaults, InjectedFlushFailureKeepsThePreviousFile) {
  EXPECT_TRUE(contains(injectedFailure(FileStep::kFsync, EIO), "flushing")) << "names the step";
}

TEST_F(FileFaults, InjectedRenameFailureKeepsThePreviousFile) {
  EXPECT_TRUE(contains(injectedFailure(FileStep::kRename, EIO), "renaming")) << "names the step";
}

TEST_F(FileFaults, InjectedReadOnlyFolderNamesTheFolderAndKeepsThePreviousFile) {
  for (const int error_number : {EROFS, EACCES}) {
    const std::string error = injectedFailure(FileStep::kOpen, error_number);
    EXPECT_TRUE(contains(error, "folder '" + dir_.string() + "'")) << error;
  }
}

TEST_F(FileFaults, InjectedFullDiskWhileWritingAMeshKeepsThePreviousMesh) {
  const fs::path path = dir_ / "mesh.ply";
  Mesh triangle;
  triangle.vertices = {Eigen::Vector3f(0, 0, 0), Eigen::Vector3f(1, 0, 0),
                       Eigen::Vector3f(0, 1, 0)};
  triangle.triangles = {Eigen::Vector3i(0, 1, 2)};
  writePly(path.string(), triangle);
  const std::vector<std::uint8_t> previous = readFile(path.string());
  const ScopedFileFault fault(FileStep::kWrite, ENOSPC);
  try {
    writePly(path.string(), extractMesh(big_));
    ADD_FAILURE() << "writing the mesh should have failed";
  } catch (const Error& e) {
    EXPECT_TRUE(contains(e.what(), path.string())) << e.what();
    EXPECT_TRUE(contains(e.what(), "No space left on device")) << e.what();
  }
  expectPreviousKept(path, previous);
}

TEST_F(FileFaults, MissingFolderNamesTheFolder) {
  const fs::path path = dir_ / "no_such_folder" / "map.strata";
  const std::string error = failedSave(small_, path);
  EXPECT_TRUE(contains(error, "folder '" + path.parent_path().string() + "'")) << error;
  EXPECT_TRUE(contains(error, std::strerror(ENOENT))) << error;
}

TEST_F(FileFaults, FullTmpfsKeepsThePreviousFile) {
  ScopedTmpfs tmpfs(dir_ / "small_fs", "size=64k");
  STRATA_REQUIRE_MOUNT(tmpfs);
  const fs::path path = dir_ / "small_fs" / "map.strata";
  const std::vector<std::uint8_t> previous = savePrevious(path);
  ASSERT_GT(serializeMap(big_).size(), 64u * 1024u) << "the new map must not fit";
  const std::string error = failedSave(big_, path);
  EXPECT_TRUE(contains(error, path.string())) << error;
  EXPECT_TRUE(contains(error, "No space left on device")) << error;
  expectPreviousKept(path, previous);
  EXPECT_EQ(loadMap(path.string()).blockCount(), small_.blockCount());
}

TEST_F(FileFaults, ReadOnlyTmpfsNamesTheFolderAndKeepsThePreviousFile) {
  ScopedTmpfs tmpfs(dir_ / "ro_fs", "size=1m");
  STRATA_REQUIRE_MOUNT(tmpfs);
  const fs::path path = dir_ / "ro_fs" / "map.strata";
  const std::vector<std::uint8_t> previous = savePrevious(path);
  ASSERT_TRUE(tmpfs.makeReadOnly()) << std::strerror(errno);
  const std::string error = failedSave(big_, path);
  EXPECT_TRUE(contains(error, "folder '" + path.parent_path().string() + "'")) << error;
  EXPECT_TRUE(contains(error, std::strerror(EROFS))) << error;
  expectPreviousKept(path, previous);
}

}  // namespace
}  // namespace strata
