// writePly: the whole file is serialised in memory, then written to a temporary file in the target
// directory and renamed over the target (rename within one file system is atomic on POSIX).
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <system_error>

#include "core/error.h"
#include "mesh/ply.h"

// NOTE: the body is copied from memory as is; PLY here is little-endian.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "writePly assumes a little-endian host");

namespace strata {
namespace {

template <typename T>
void append(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

void checkConsistent(const std::string& path, const Mesh& mesh) {
  const std::size_t n = mesh.vertices.size();
  if ((mesh.hasNormals() && mesh.normals.size() != n) ||
      (mesh.hasColors() && mesh.colors.size() != n)) {
    throw Error("cannot write PLY '" + path + "': normals/colours do not match the vertex count");
  }
  for (const Eigen::Vector3i& tri : mesh.triangles) {
    if ((tri.array() < 0).any() || (tri.array() >= static_cast<int>(n)).any()) {
      throw Error("cannot write PLY '" + path + "': a triangle references a missing vertex");
    }
  }
}

std::string serialise(const Mesh& mesh) {
  std::ostringstream header;
  header << "ply\nformat binary_little_endian 1.0\ncomment written by strata\n"
         << "element vertex " << mesh.vertices.size() << "\n"
         << "property float x\nproperty float y\nproperty float z\n";
  if (mesh.hasNormals()) header << "property float nx\nproperty float ny\nproperty float nz\n";
  if (mesh.hasColors()) header << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  header << "element face " << mesh.triangles.size() << "\n"
         << "property list uchar int vertex_indices\nend_header\n";
  std::string out = header.str();
  const std::size_t vertex_bytes = 12 + (mesh.hasNormals() ? 12 : 0) + (mesh.hasColors() ? 3 : 0);
  out.reserve(out.size() + mesh.vertices.size() * vertex_bytes + mesh.triangles.size() * 13);
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    for (int k = 0; k < 3; ++k) append(out, mesh.vertices[i][k]);
    if (mesh.hasNormals()) {
      for (int k = 0; k < 3; ++k) append(out, mesh.normals[i][k]);
    }
    if (mesh.hasColors()) out.append(reinterpret_cast<const char*>(mesh.colors[i].data()), 3);
  }
  for (const Eigen::Vector3i& tri : mesh.triangles) {
    append(out, std::uint8_t{3});
    for (int k = 0; k < 3; ++k) append(out, static_cast<std::int32_t>(tri[k]));
  }
  return out;
}

/// A temporary file beside the target; removed on destruction unless committed.
class TempFile {
 public:
  explicit TempFile(const std::string& target) : target_(target) {
    static std::atomic<unsigned> counter{0};
    const std::filesystem::path p(target);
    path_ = (p.parent_path() / ("." + p.filename().string() + ".tmp." + std::to_string(getpid()) +
                                "." + std::to_string(counter++)))
                .string();
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd_ < 0) fail("cannot create temporary file '" + path_ + "'", errno);
  }
  ~TempFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!committed_) ::unlink(path_.c_str());
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  void write(const std::string& data) {
    std::size_t done = 0;
    while (done < data.size()) {
      const ssize_t n = ::write(fd_, data.data() + done, data.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) fail("write failed", errno);
      done += static_cast<std::size_t>(n);
    }
  }

  /// Flushes to disk and renames over the target.
  void commit() {
    if (::fsync(fd_) != 0) fail("fsync failed", errno);
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail("close failed", errno);
    std::error_code ec;
    std::filesystem::rename(path_, target_, ec);
    if (ec) fail("rename from '" + path_ + "' failed", ec.value());
    committed_ = true;
  }

 private:
  [[noreturn]] void fail(const std::string& what, int error) const {
    throw Error("cannot write PLY '" + target_ + "': " + what + ": " + std::strerror(error));
  }

  std::string target_;
  std::string path_;
  int fd_ = -1;
  bool committed_ = false;
};

}  // namespace

void writePly(const std::string& path, const Mesh& mesh) {
  checkConsistent(path, mesh);
  const std::string data = serialise(mesh);
  TempFile file(path);
  file.write(data);
  file.commit();
}

}  // namespace strata
