#include "strata/store/schema.h"

#include <string>

#include "strata/core/error.h"
#include "strata/store/sqlite_db.h"

namespace strata::store {

namespace {

/// The seven columns of one pose: translation (metres) and unit quaternion (x, y, z, w).
std::string poseColumnDefinitions(const std::string& prefix, bool nullable) {
  std::string out;
  for (const char* c : {"tx", "ty", "tz", "qx", "qy", "qz", "qw"}) {
    out += "  " + prefix + "_" + c + (nullable ? " REAL,\n" : " REAL NOT NULL,\n");
  }
  return out;
}

/// All seven columns NULL or none (a pose is never half stored).
std::string allOrNone(const std::string& prefix) {
  std::string nulls, values;
  for (const char* c : {"tx", "ty", "tz", "qx", "qy", "qz", "qw"}) {
    nulls += std::string(nulls.empty() ? "" : " AND ") + prefix + "_" + c + " IS NULL";
    values += std::string(values.empty() ? "" : " AND ") + prefix + "_" + c + " IS NOT NULL";
  }
  return "  CHECK ((" + nulls + ") OR (" + values + "))";
}

std::string schemaV1() {
  return "CREATE TABLE sessions (\n"
         "  id INTEGER PRIMARY KEY,\n"
         "  name TEXT NOT NULL,\n"
         "  source_folder TEXT NOT NULL UNIQUE,\n"
         "  created_unix_s REAL NOT NULL,\n" +
         poseColumnDefinitions("T_W_S", true) +
         "  aligned INTEGER NOT NULL DEFAULT 0 CHECK (aligned IN (0, 1)),\n" + allOrNone("T_W_S") +
         ",\n  CHECK (aligned = 0 OR T_W_S_tx IS NOT NULL));\n"
         "CREATE TABLE keyframes (\n"
         "  id INTEGER PRIMARY KEY,\n"
         "  session_id INTEGER NOT NULL REFERENCES sessions(id) ON DELETE CASCADE,\n"
         "  timestamp_s REAL NOT NULL,\n" +
         poseColumnDefinitions("T_S_C", false) + poseColumnDefinitions("T_W_C", true) +
         "  covariance BLOB CHECK (covariance IS NULL OR length(covariance) = 288),\n" +
         allOrNone("T_W_C") +
         ");\n"
         "CREATE INDEX keyframes_by_session_time ON keyframes(session_id, timestamp_s);\n"
         "CREATE TABLE edges (\n"
         "  id INTEGER PRIMARY KEY,\n"
         "  kind TEXT NOT NULL CHECK (kind IN ('odometry', 'loop', 'prior')),\n"
         "  from_keyframe INTEGER NOT NULL REFERENCES keyframes(id) ON DELETE CASCADE,\n"
         "  to_keyframe INTEGER REFERENCES keyframes(id) ON DELETE CASCADE,\n" +
         poseColumnDefinitions("T_from_to", false) +
         "  information BLOB NOT NULL CHECK (length(information) = 288),\n"
         "  loop_inliers INTEGER,\n"
         "  loop_inlier_ratio REAL,\n"
         "  loop_residual REAL,\n"
         "  loop_accepted INTEGER CHECK (loop_accepted IS NULL OR loop_accepted IN (0, 1)),\n"
         "  CHECK ((kind = 'prior') = (to_keyframe IS NULL)),\n"
         "  CHECK ((kind = 'loop') = (loop_accepted IS NOT NULL)));\n"
         "CREATE INDEX edges_by_kind ON edges(kind);\n"
         "CREATE INDEX edges_by_from ON edges(from_keyframe);\n"
         "CREATE INDEX edges_by_to ON edges(to_keyframe);\n"
         "CREATE TABLE features (\n"
         "  keyframe_id INTEGER PRIMARY KEY REFERENCES keyframes(id) ON DELETE CASCADE,\n"
         "  format TEXT NOT NULL,\n"
         "  count INTEGER NOT NULL CHECK (count >= 0),\n"
         "  descriptor_bytes INTEGER NOT NULL CHECK (descriptor_bytes >= 0),\n"
         "  data BLOB NOT NULL CHECK (length(data) = count * (8 + descriptor_bytes)));\n"
         "CREATE TABLE resources (\n"
         "  id INTEGER PRIMARY KEY,\n"
         "  session_id INTEGER NOT NULL REFERENCES sessions(id) ON DELETE CASCADE,\n"
         "  keyframe_id INTEGER REFERENCES keyframes(id) ON DELETE CASCADE,\n"
         "  kind TEXT NOT NULL CHECK (kind IN ('depth', 'color', 'tsdf_layer')),\n"
         "  relative_path TEXT NOT NULL,\n"
         "  byte_size INTEGER NOT NULL CHECK (byte_size >= 0),\n"
         "  crc32 INTEGER NOT NULL);\n"
         "CREATE INDEX resources_by_session ON resources(session_id);\n"
         "CREATE INDEX resources_by_keyframe ON resources(keyframe_id);\n";
}

/// Version 2: the object database (objects/object_database_file.h), one row holding its file's
/// bytes and their format version.
std::string schemaV2() {
  return "CREATE TABLE object_database (\n"
         "  id INTEGER PRIMARY KEY CHECK (id = 1),\n"
         "  format_version INTEGER NOT NULL CHECK (format_version >= 1),\n"
         "  data BLOB NOT NULL);\n";
}

/// Step i takes a file from version i to i + 1.
struct Migration {
  int from_version;
  std::string sql;
};

std::string fileVersions(const Database& db, std::int64_t version) {
  return "map database '" + db.path() + "' has schema version " + std::to_string(version);
}

}  // namespace

void checkSchema(Database& db) {
  const std::int64_t version = db.queryInt("PRAGMA user_version", "read the schema version");
  if (version > kSchemaVersion) {
    throw InputError(fileVersions(db, version) + ", newer than version " +
                     std::to_string(kSchemaVersion) +
                     " that this build reads; open it with a newer strata");
  }
  if (version < 0) throw InputError(fileVersions(db, version) + ", which is invalid");
  const std::int64_t application_id =
      db.queryInt("PRAGMA application_id", "read the application id");
  const std::int64_t tables =
      db.queryInt("SELECT COUNT(*) FROM sqlite_schema WHERE type = 'table'", "list tables");
  if (application_id != kApplicationId && (version != 0 || tables != 0)) {
    throw InputError("map database '" + db.path() +
                     "' is an SQLite file of another application (application_id " +
                     std::to_string(application_id) + ", " + std::to_string(tables) +
                     " tables), not a Strata map");
  }
}

void migrate(Database& db) {
  checkSchema(db);
  const std::int64_t version = db.queryInt("PRAGMA user_version", "read the schema version");
  const Migration migrations[] = {{0, schemaV1()}, {1, schemaV2()}};
  for (const Migration& m : migrations) {
    if (m.from_version < version) continue;
    Transaction transaction(db);
    db.exec(m.sql, "migrate the schema");
    db.exec("PRAGMA application_id = " + std::to_string(kApplicationId) +
                "; PRAGMA user_version = " + std::to_string(m.from_version + 1),
            "set the schema version");
    transaction.commit();
  }
}

}  // namespace strata::store
