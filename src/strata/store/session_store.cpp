#include "strata/store/session_store.h"

#include <chrono>
#include <cmath>
#include <filesystem>

#include "strata/core/error.h"
#include "strata/store/internal/store_sql.h"
#include "strata/store/schema.h"

namespace strata::store {

namespace fs = std::filesystem;
using detail::bindPose;
using detail::placeholders;
using detail::poseColumns;
using detail::readPose;

namespace {

std::string absoluteFolder(const std::string& folder) {
  std::string out = fs::absolute(fs::path(folder)).lexically_normal().string();
  while (out.size() > 1 && out.back() == '/') out.pop_back();
  return out;
}

void checkFinite(const Eigen::Isometry3d& T, const std::string& what) {
  if (!T.matrix().allFinite()) throw InputError(what + ": non-finite pose");
}

/// The file must pass SQLite's structural check before anything trusts it.
void quickCheck(Database& db) {
  Statement check(db, "PRAGMA quick_check");
  std::string first;
  if (check.step()) first = check.getText(0);
  if (first != "ok") {
    throw InputError("map database '" + db.path() + "' is damaged (PRAGMA quick_check: " + first +
                     ")");
  }
}

const std::string kSessionColumns =
    "id, name, source_folder, created_unix_s, " + poseColumns("T_W_S") + ", aligned";

}  // namespace

Store::Store(const std::string& path, const StoreOptions& options) {
  const fs::path file(path);
  if ((!options.create || options.read_only) && !fs::exists(file)) {
    throw InputError("map database '" + path + "' does not exist");
  }
  if (fs::is_directory(file)) throw InputError("map database '" + path + "' is a folder");
  const fs::path parent = fs::absolute(file).parent_path();
  if (!fs::is_directory(parent)) {
    throw InputError("map database '" + path + "': folder '" + parent.string() +
                     "' does not exist");
  }
  folder_ = parent.lexically_normal().string();
  if (options.read_only) {
    openReadOnly(path);
    return;
  }
  db_ = std::make_unique<Database>(path, options.create);
  // NOTE: checked before the first write (switching to WAL rewrites the header), so a file that
  // is not SQLite, is newer or belongs to another application is left exactly as it was.
  checkSchema(*db_);
  db_->exec("PRAGMA journal_mode = WAL", "set the WAL journal");
  db_->exec("PRAGMA synchronous = FULL; PRAGMA foreign_keys = ON", "set durability pragmas");
  quickCheck(*db_);
  migrate(*db_);
  if (options.max_database_bytes > 0) {
    const std::int64_t page_bytes = db_->queryInt("PRAGMA page_size", "read the page size");
    const std::int64_t pages = std::max<std::int64_t>(1, options.max_database_bytes / page_bytes);
    db_->queryInt("PRAGMA max_page_count = " + std::to_string(pages), "limit the size");
  }
}

void Store::openReadOnly(const std::string& path) {
  db_ = std::make_unique<Database>(path, /*create=*/false, /*read_only=*/true);
  checkSchema(*db_);
  const std::int64_t version = db_->queryInt("PRAGMA user_version", "read the schema version");
  if (version == 0) {
    throw InputError("map database '" + path + "' is empty, not a Strata map");
  }
  if (version < kSchemaVersion) {
    throw InputError("map database '" + path + "' has schema version " + std::to_string(version) +
                     ", older than " + std::to_string(kSchemaVersion) +
                     ": it is only read here; a command that writes it (map import, align --db) "
                     "migrates it");
  }
  db_->exec("PRAGMA foreign_keys = ON", "set the foreign-key check");
  quickCheck(*db_);
}

Store::~Store() = default;

SessionRecord Store::sessionFrom(const Statement& row) const {
  SessionRecord s;
  s.id = row.getInt(0);
  s.name = row.getText(1);
  s.source_folder = row.getText(2);
  s.created_unix_s = row.getDouble(3);
  s.T_W_S = readPose(row, 4, "session " + std::to_string(s.id) + " T_W_S");
  s.aligned = row.getInt(11) != 0;
  return s;
}

void Store::requireSession(std::int64_t session_id, const std::string& what) {
  Statement s(*db_, "SELECT 1 FROM sessions WHERE id = ?");
  s.bind(1, session_id);
  if (!s.step()) {
    throw InputError("map database '" + path() + "': " + what + ": no session " +
                     std::to_string(session_id));
  }
}

std::int64_t Store::addSession(const std::string& name, const std::string& source_folder) {
  const std::string source = absoluteFolder(source_folder);
  if (findSessionBySource(source)) {
    throw InputError("map database '" + path() + "' already holds a session imported from '" +
                     source + "'");
  }
  const double now_s =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  Transaction transaction(*db_);
  Statement insert(*db_,
                   "INSERT INTO sessions (name, source_folder, created_unix_s) "
                   "VALUES (?, ?, ?)");
  insert.bind(1, name).bind(2, source).bind(3, now_s).run();
  const std::int64_t id = db_->lastInsertId();
  transaction.commit();
  return id;
}

std::optional<SessionRecord> Store::findSessionBySource(const std::string& source_folder) {
  Statement s(*db_, "SELECT " + kSessionColumns + " FROM sessions WHERE source_folder = ?");
  s.bind(1, absoluteFolder(source_folder));
  if (!s.step()) return std::nullopt;
  return sessionFrom(s);
}

std::vector<SessionRecord> Store::sessions() {
  Statement s(*db_, "SELECT " + kSessionColumns + " FROM sessions ORDER BY id");
  std::vector<SessionRecord> out;
  while (s.step()) out.push_back(sessionFrom(s));
  return out;
}

std::vector<std::int64_t> Store::addKeyframes(const std::vector<KeyframeRecord>& keyframes) {
  Transaction transaction(*db_);
  Statement insert(*db_, "INSERT INTO keyframes (session_id, timestamp_s, " + poseColumns("T_S_C") +
                             ", " + poseColumns("T_W_C") + ", covariance) VALUES (" +
                             placeholders(17) + ")");
  std::vector<std::int64_t> ids;
  ids.reserve(keyframes.size());
  std::int64_t checked_session = 0;
  for (const KeyframeRecord& k : keyframes) {
    const std::string what = "keyframe at " + std::to_string(k.timestamp_s) + " s";
    if (k.session_id != checked_session) {
      requireSession(k.session_id, what);
      checked_session = k.session_id;
    }
    if (!std::isfinite(k.timestamp_s)) throw InputError(what + ": non-finite timestamp");
    checkFinite(k.T_S_C, what + " T_S_C");
    if (k.T_W_C) checkFinite(*k.T_W_C, what + " T_W_C");
    if (k.covariance && !k.covariance->allFinite()) {
      throw InputError(what + ": non-finite covariance");
    }
    insert.bind(1, k.session_id).bind(2, k.timestamp_s);
    bindPose(insert, 3, k.T_S_C);
    bindPose(insert, 10, k.T_W_C);
    if (k.covariance) {
      insert.bindBlob(17, matrixToBlob(*k.covariance));
    } else {
      insert.bindNull(17);
    }
    insert.run();
    ids.push_back(db_->lastInsertId());
  }
  transaction.commit();
  return ids;
}

std::vector<KeyframeRecord> Store::keyframes(std::int64_t session_id) {
  Statement s(*db_, "SELECT id, session_id, timestamp_s, " + poseColumns("T_S_C") + ", " +
                        poseColumns("T_W_C") +
                        ", covariance FROM keyframes WHERE session_id = ? "
                        "ORDER BY timestamp_s, id");
  s.bind(1, session_id);
  std::vector<KeyframeRecord> out;
  while (s.step()) {
    KeyframeRecord k;
    k.id = s.getInt(0);
    const std::string what = "map database '" + path() + "': keyframe " + std::to_string(k.id);
    k.session_id = s.getInt(1);
    k.timestamp_s = s.getDouble(2);
    k.T_S_C = *readPose(s, 3, what + " T_S_C");
    k.T_W_C = readPose(s, 10, what + " T_W_C");
    if (!s.isNull(17)) k.covariance = matrixFromBlob(s.getBlob(17), what + " covariance");
    out.push_back(std::move(k));
  }
  return out;
}

void Store::setOptimisedPoses(
    const std::vector<std::pair<std::int64_t, Eigen::Isometry3d>>& T_W_C) {
  Transaction transaction(*db_);
  Statement update(*db_, "UPDATE keyframes SET (" + poseColumns("T_W_C") + ") = (" +
                             placeholders(7) + ") WHERE id = ?");
  for (const auto& [id, pose] : T_W_C) {
    checkFinite(pose, "optimised pose of keyframe " + std::to_string(id));
    bindPose(update, 1, pose);
    update.bind(8, id).run();
    if (db_->changes() != 1) {
      throw InputError("map database '" + path() + "': setOptimisedPoses: no keyframe " +
                       std::to_string(id));
    }
  }
  transaction.commit();
}

void Store::setSessionAlignment(std::int64_t session_id, const Eigen::Isometry3d& T_W_S) {
  checkFinite(T_W_S, "alignment of session " + std::to_string(session_id));
  Transaction transaction(*db_);
  requireSession(session_id, "setSessionAlignment");
  Statement update(*db_, "UPDATE sessions SET (" + poseColumns("T_W_S") + ", aligned) = (" +
                             placeholders(7) + ", 1) WHERE id = ?");
  bindPose(update, 1, T_W_S);
  update.bind(8, session_id).run();
  transaction.commit();
}

void Store::clearAlignment() {
  Transaction transaction(*db_);
  Statement(*db_, "UPDATE sessions SET (" + poseColumns("T_W_S") + ", aligned) = (" +
                      "NULL, NULL, NULL, NULL, NULL, NULL, NULL, 0)").run();
  Statement(*db_, "UPDATE keyframes SET (" + poseColumns("T_W_C") + ") = (" +
                      "NULL, NULL, NULL, NULL, NULL, NULL, NULL)").run();
  Statement(*db_, "DELETE FROM edges WHERE kind = 'loop'").run();
  transaction.commit();
}

}  // namespace strata::store
