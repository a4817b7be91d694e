#pragma once
// The map database's schema and its migrations (docs/store.md lists every table and column).
#include <cstdint>

namespace strata::store {

class Database;

/// The schema version this build writes (PRAGMA user_version).
constexpr int kSchemaVersion = 2;
/// PRAGMA application_id of a Strata map: "STRA".
constexpr std::int32_t kApplicationId = 0x53545241;

/// Refuses, without writing anything, a file this build must not touch: InputError naming the
/// file and both versions for a schema newer than kSchemaVersion, and for a file with tables that
/// is not a Strata map (another application id, or none and version 0). The first read of the
/// file: one that is not SQLite fails here ("file is not a database").
void checkSchema(Database& db);

/// Brings an open database to kSchemaVersion, each migration step in its own transaction (a
/// crash between steps leaves a file at an older version that the next open continues from).
/// Version 0 is an empty SQLite file (just created, or made by another tool with no tables).
/// Runs checkSchema() first.
void migrate(Database& db);

}  // namespace strata::store
