// Store: files beside the database (resources) and the per-session summary.
#include <filesystem>
#include <system_error>

#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/store/internal/store_sql.h"
#include "strata/store/session_store.h"

namespace strata::store {

namespace fs = std::filesystem;

namespace {

std::uint32_t crcOf(const std::vector<std::uint8_t>& bytes) {
  return crc32(bytes.data(), bytes.size());
}

std::string hex(std::uint32_t value) {
  char text[16];
  std::snprintf(text, sizeof(text), "%08x", value);
  return text;
}

const char* kResourceColumns =
    "id, session_id, keyframe_id, kind, relative_path, byte_size, crc32 FROM resources";

ResourceRecord resourceFrom(const Statement& s, const std::string& db_path) {
  ResourceRecord r;
  r.id = s.getInt(0);
  r.session_id = s.getInt(1);
  if (!s.isNull(2)) r.keyframe_id = s.getInt(2);
  r.kind = parseResourceKind(s.getText(3),
                             "map database '" + db_path + "': resource " + std::to_string(r.id));
  r.relative_path = s.getText(4);
  r.byte_size = static_cast<std::uint64_t>(s.getInt(5));
  r.crc32 = static_cast<std::uint32_t>(s.getInt(6));
  return r;
}

}  // namespace

std::string Store::resourcePath(const ResourceRecord& resource) const {
  const fs::path relative(resource.relative_path);
  return relative.is_absolute() ? relative.string()
                                : (fs::path(folder_) / relative).lexically_normal().string();
}

std::int64_t Store::attachResource(std::int64_t session_id, std::optional<std::int64_t> keyframe_id,
                                   ResourceKind kind, const std::string& file, AttachMode mode) {
  requireSession(session_id, "attachResource");
  const std::vector<std::uint8_t> bytes = readFile(file);
  fs::path placed = fs::absolute(file).lexically_normal();
  if (mode == AttachMode::kCopy) {
    const fs::path folder = fs::path(folder_) / (fs::path(path()).stem().string() + ".resources") /
                            ("session_" + std::to_string(session_id)) / resourceKindName(kind);
    fs::create_directories(folder);
    placed = folder / fs::path(file).filename();
    if (fs::exists(placed) && readFile(placed.string()) != bytes) {
      throw InputError("map database '" + path() + "': cannot copy '" + file + "': '" +
                       placed.string() + "' already holds another file");
    }
    writeFileAtomically(placed.string(), bytes);
  }
  std::error_code ec;
  fs::path relative = fs::relative(placed, folder_, ec);
  if (ec || relative.empty()) relative = placed;  // another root: keep it absolute
  Transaction transaction(*db_);
  Statement insert(*db_,
                   "INSERT INTO resources (session_id, keyframe_id, kind, relative_path, "
                   "byte_size, crc32) VALUES (?, ?, ?, ?, ?, ?)");
  insert.bind(1, session_id).bind(2, keyframe_id).bind(3, std::string(resourceKindName(kind)));
  insert.bind(4, relative.generic_string()).bind(5, static_cast<std::int64_t>(bytes.size()));
  insert.bind(6, static_cast<std::int64_t>(crcOf(bytes)));
  insert.run();
  const std::int64_t id = db_->lastInsertId();
  transaction.commit();
  return id;
}

std::vector<ResourceRecord> Store::resources(std::optional<std::int64_t> session_id) {
  Statement s(*db_, std::string("SELECT ") + kResourceColumns +
                        " WHERE ? IS NULL OR session_id = ? ORDER BY id");
  s.bind(1, session_id).bind(2, session_id);
  std::vector<ResourceRecord> out;
  while (s.step()) out.push_back(resourceFrom(s, path()));
  return out;
}

std::vector<std::uint8_t> Store::readResource(std::int64_t resource_id) {
  Statement s(*db_, std::string("SELECT ") + kResourceColumns + " WHERE id = ?");
  s.bind(1, resource_id);
  if (!s.step()) {
    throw InputError("map database '" + path() + "': no resource " + std::to_string(resource_id));
  }
  const ResourceRecord r = resourceFrom(s, path());
  const std::string file = resourcePath(r);
  if (!fs::exists(file)) throw InputError("resource '" + file + "' is missing");
  const std::vector<std::uint8_t> bytes = readFile(file);
  if (bytes.size() != r.byte_size || crcOf(bytes) != r.crc32) {
    throw InputError("resource '" + file +
                     "' changed since it was attached: " + std::to_string(bytes.size()) +
                     " bytes, CRC-32 " + hex(crcOf(bytes)) + ", attached " +
                     std::to_string(r.byte_size) + " bytes, CRC-32 " + hex(r.crc32));
  }
  return bytes;
}

std::vector<ResourceProblem> Store::verifyResources(std::optional<std::int64_t> session_id) {
  std::vector<ResourceProblem> problems;
  for (const ResourceRecord& r : resources(session_id)) {
    const std::string file = resourcePath(r);
    std::error_code ec;
    const auto size = fs::file_size(file, ec);
    if (ec) {
      problems.push_back({r, ResourceProblem::Kind::kMissing,
                          "resource '" + file + "' is missing: " + ec.message()});
    } else if (size != r.byte_size) {
      problems.push_back({r, ResourceProblem::Kind::kSizeChanged,
                          "resource '" + file + "' has " + std::to_string(size) +
                              " bytes, attached with " + std::to_string(r.byte_size)});
    } else if (const std::uint32_t crc = crcOf(readFile(file)); crc != r.crc32) {
      problems.push_back(
          {r, ResourceProblem::Kind::kChecksumChanged,
           "resource '" + file + "' has CRC-32 " + hex(crc) + ", attached with " + hex(r.crc32)});
    }
  }
  return problems;
}

std::vector<SessionSummary> Store::summary() {
  std::vector<SessionSummary> out;
  Statement edge_counts(*db_,
                        "SELECT e.kind, COUNT(*) FROM edges e JOIN keyframes k ON "
                        "e.from_keyframe = k.id WHERE k.session_id = ? GROUP BY e.kind");
  Statement resource_counts(*db_,
                            "SELECT COUNT(*), COALESCE(SUM(byte_size), 0) FROM resources "
                            "WHERE session_id = ?");
  for (SessionRecord& session : sessions()) {
    SessionSummary s;
    const std::vector<KeyframeRecord> keyframes = this->keyframes(session.id);
    s.keyframes = keyframes.size();
    for (std::size_t i = 0; i < keyframes.size(); ++i) {
      if (keyframes[i].T_W_C) ++s.optimised_keyframes;
      if (i > 0) {
        s.path_length_m +=
            (keyframes[i].T_S_C.translation() - keyframes[i - 1].T_S_C.translation()).norm();
      }
    }
    if (!keyframes.empty()) {
      s.first_timestamp_s = keyframes.front().timestamp_s;
      s.last_timestamp_s = keyframes.back().timestamp_s;
    }
    edge_counts.bind(1, session.id);
    while (edge_counts.step()) {
      const auto count = static_cast<std::size_t>(edge_counts.getInt(1));
      switch (parseEdgeKind(edge_counts.getText(0), "map database '" + path() + "'")) {
        case EdgeKind::kOdometry:
          s.odometry_edges = count;
          break;
        case EdgeKind::kLoop:
          s.loop_edges = count;
          break;
        case EdgeKind::kPrior:
          s.prior_edges = count;
          break;
      }
    }
    edge_counts.reset();
    resource_counts.bind(1, session.id);
    if (resource_counts.step()) {
      s.resources = static_cast<std::size_t>(resource_counts.getInt(0));
      s.resource_bytes = static_cast<std::uint64_t>(resource_counts.getInt(1));
    }
    resource_counts.reset();
    s.session = std::move(session);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace strata::store
