// Store: the object database's copy (one row of table object_database).
#include "strata/core/error.h"
#include "strata/store/session_store.h"

namespace strata::store {

void Store::setObjectDatabase(const ObjectDatabaseBlob& blob) {
  if (blob.format_version == 0 || blob.bytes.empty()) {
    throw InputError("map database '" + path() + "': an object database needs a format version " +
                     "(got " + std::to_string(blob.format_version) + ") and bytes (got " +
                     std::to_string(blob.bytes.size()) + ")");
  }
  Transaction transaction(*db_);
  Statement replace(*db_,
                    "INSERT OR REPLACE INTO object_database (id, format_version, data) "
                    "VALUES (1, ?, ?)");
  replace.bind(1, static_cast<std::int64_t>(blob.format_version)).bindBlob(2, blob.bytes);
  replace.run();
  transaction.commit();
}

std::optional<ObjectDatabaseBlob> Store::objectDatabase() {
  Statement s(*db_, "SELECT format_version, data FROM object_database WHERE id = 1");
  if (!s.step()) return std::nullopt;
  ObjectDatabaseBlob blob;
  blob.format_version = static_cast<std::uint32_t>(s.getInt(0));
  blob.bytes = s.getBlob(1);
  return blob;
}

}  // namespace strata::store
