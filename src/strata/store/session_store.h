#pragma once
// The session store: one SQLite file per map holding many sessions (missions), each in its own
// odometry frame, with keyframes, pose-graph edges, features and the files they refer to, for
// multi-session alignment to work on. Schema, frames and units: docs/store.md and store_types.h.
//
// Durability: the file is in WAL mode with synchronous=FULL and foreign keys on. Every public
// write is one transaction (all or nothing); batches of calls share one through
// beginTransaction(). A crash (or SIGKILL) at any moment leaves the last committed state.
// Errors: strata::InputError for a file that is not a usable map (missing with create = false,
// not SQLite, corrupt or truncated, a newer schema, records that break the contracts below);
// strata::Error for failed writes (read-only folder, full disk: SQLITE_FULL), both naming the
// file and SQLite's message. A failed write rolls its transaction back; what was committed stays.
// Thread safety: a Store belongs to one thread at a time. Several Stores (threads or processes)
// may open one file: readers run alongside one writer; a writer waits up to 5 s for another.
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "strata/store/sqlite_db.h"
#include "strata/store/store_types.h"

namespace strata::store {

struct StoreOptions {
  /// Create the file (and its schema) when absent; false: a missing file is an InputError.
  bool create = true;
  /// Upper bound on the database file's size, 0 = none. Writes that would pass it fail as a full
  /// disk does (SQLITE_FULL), which also makes that path testable.
  std::int64_t max_database_bytes = 0;
  /// Open for reading only (what `map info` and `map export` do): the file is never changed (no
  /// creation, journal switch or migration). A missing or empty file, a file that is not a Strata
  /// map and one of an older schema (which would need migrating) are InputErrors; every write
  /// throws Error. `create` is ignored.
  bool read_only = false;
};

/// The object database's copy in the map (objects/object_database_file.h writes and reads it).
struct ObjectDatabaseBlob {
  std::uint32_t format_version = 0;  // of the bytes' own format
  std::vector<std::uint8_t> bytes;
};

/// How attachResource() places the file.
enum class AttachMode {
  kReference,  // leave it where it is; store its path relative to the database's folder
  kCopy,       // copy it into <database stem>.resources/session_<id>/ beside the database
};

class Store {
 public:
  /// Opens or creates `path`, migrating an older schema (schema.h) and checking the file
  /// (PRAGMA quick_check), so a damaged file is refused here rather than half-read later.
  explicit Store(const std::string& path, const StoreOptions& options = {});
  Store(Store&&) noexcept = default;
  ~Store();

  const std::string& path() const { return db_->path(); }
  /// The folder resource paths are relative to (the database's folder, absolute).
  const std::string& folder() const { return folder_; }

  /// Groups the writes made while it lives into one transaction (commit() or all are undone).
  Transaction beginTransaction() { return Transaction(*db_); }

  /// A new session, unaligned, created now. InputError when `source_folder` (made absolute) is
  /// already in the map. Returns its id.
  std::int64_t addSession(const std::string& name, const std::string& source_folder);
  /// The session imported from `source_folder` (made absolute), if any.
  std::optional<SessionRecord> findSessionBySource(const std::string& source_folder);
  /// Appends keyframes (their ids ignored); returns the new ids in order. InputError for an
  /// unknown session or a non-finite timestamp / pose / covariance.
  std::vector<std::int64_t> addKeyframes(const std::vector<KeyframeRecord>& keyframes);
  /// Appends edges (ids ignored); InputError for unknown keyframes, a prior with a `to` or
  /// another kind without one, or loop statistics on anything but a loop (and none on a loop).
  std::vector<std::int64_t> addEdges(const std::vector<EdgeRecord>& edges);
  /// Sets T_W_C of existing keyframes; InputError naming an unknown id (nothing is written then).
  void setOptimisedPoses(const std::vector<std::pair<std::int64_t, Eigen::Isometry3d>>& T_W_C);
  /// Sets T_W_S and marks the session aligned; InputError for an unknown session.
  void setSessionAlignment(std::int64_t session_id, const Eigen::Isometry3d& T_W_S);
  /// Forgets every alignment result: sessions unaligned (T_W_S NULL), optimised keyframe poses
  /// NULL, loop edges deleted; odometry edges, priors, features and resources stay. One
  /// transaction, so a new alignment replaces the old one whole.
  void clearAlignment();
  /// Stores (replaces) a keyframe's features.
  void setFeatures(std::int64_t keyframe_id, const FeatureSet& features);
  std::optional<FeatureSet> features(std::int64_t keyframe_id);

  /// Records `file` as a resource: its size and CRC-32 now, its path relative to folder() (after
  /// copying it there with kCopy). InputError when the file cannot be read or the ids are unknown.
  std::int64_t attachResource(std::int64_t session_id, std::optional<std::int64_t> keyframe_id,
                              ResourceKind kind, const std::string& file, AttachMode mode);
  /// The resource's bytes, checked: InputError naming the file when it is missing or its size or
  /// CRC-32 differ from what was attached.
  std::vector<std::uint8_t> readResource(std::int64_t resource_id);
  /// Every resource (of one session, or all) whose file is missing or changed.
  std::vector<ResourceProblem> verifyResources(std::optional<std::int64_t> session_id = {});
  /// The absolute path of a resource's file.
  std::string resourcePath(const ResourceRecord& resource) const;

  /// Stores the object database's bytes (table object_database, one row), replacing any earlier
  /// copy in one transaction. InputError for an empty blob or format version 0.
  void setObjectDatabase(const ObjectDatabaseBlob& blob);
  /// The stored copy; nullopt when the map holds none.
  std::optional<ObjectDatabaseBlob> objectDatabase();

  std::vector<SessionRecord> sessions();
  /// A session's keyframes in time order.
  std::vector<KeyframeRecord> keyframes(std::int64_t session_id);
  /// Edges of one kind (or all), in id order.
  std::vector<EdgeRecord> edges(std::optional<EdgeKind> kind = {});
  std::vector<ResourceRecord> resources(std::optional<std::int64_t> session_id = {});
  /// Counts, path length and time span per session, in id order.
  std::vector<SessionSummary> summary();

 private:
  void openReadOnly(const std::string& path);
  SessionRecord sessionFrom(const Statement& row) const;
  void requireSession(std::int64_t session_id, const std::string& what);

  std::unique_ptr<Database> db_;
  std::string folder_;
};

}  // namespace strata::store
