#include "strata/store/sqlite_db.h"

#include <sqlite3.h>

#include "strata/core/error.h"

namespace strata::store {

namespace {

/// The codes that mean the file itself is not a usable database (as opposed to a failed write).
bool isInputProblem(int rc) {
  const int primary = rc & 0xff;
  return primary == SQLITE_NOTADB || primary == SQLITE_CORRUPT || primary == SQLITE_CANTOPEN;
}

}  // namespace

Database::Database(const std::string& path, bool create, bool read_only) : path_(path) {
  const int access = read_only ? SQLITE_OPEN_READONLY
                               : SQLITE_OPEN_READWRITE | (create ? SQLITE_OPEN_CREATE : 0);
  const int flags = access | SQLITE_OPEN_NOMUTEX | SQLITE_OPEN_EXRESCODE;
  const int rc = sqlite3_open_v2(path.c_str(), &db_, flags, nullptr);
  if (rc != SQLITE_OK) {
    const std::string message = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
    sqlite3_close(db_);
    db_ = nullptr;
    throw InputError("map database '" + path + "': cannot open: " + message);
  }
  // NOTE: another process (or Store) writing the same file holds the lock for one batch; wait
  // for it rather than fail at once.
  sqlite3_busy_timeout(db_, 5000);
}

Database::~Database() { sqlite3_close(db_); }

void Database::fail(int rc, const char* step) const {
  std::string message = sqlite3_errmsg(db_);
  if (message != sqlite3_errstr(rc)) message += std::string(" (") + sqlite3_errstr(rc) + ")";
  const std::string what = "map database '" + path_ + "': " + step + ": " + message;
  if (isInputProblem(rc)) throw InputError(what);
  throw Error(what);
}

std::int64_t Database::changes() const { return sqlite3_changes64(db_); }

std::int64_t Database::lastInsertId() const { return sqlite3_last_insert_rowid(db_); }

void Database::exec(const std::string& sql, const char* step) {
  const int rc = sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr);
  if (rc != SQLITE_OK) fail(rc, step);
}

std::int64_t Database::queryInt(const std::string& sql, const char* step) {
  sqlite3_stmt* stmt = nullptr;
  int rc = sqlite3_prepare_v2(db_, sql.c_str(), -1, &stmt, nullptr);
  if (rc != SQLITE_OK) fail(rc, step);
  rc = sqlite3_step(stmt);
  if (rc != SQLITE_ROW) {
    sqlite3_finalize(stmt);
    fail(rc == SQLITE_DONE ? SQLITE_ERROR : rc, step);
  }
  const std::int64_t value = sqlite3_column_int64(stmt, 0);
  sqlite3_finalize(stmt);
  return value;
}

Statement::Statement(Database& db, const std::string& sql) : db_(db) {
  const int rc = sqlite3_prepare_v2(db.handle(), sql.c_str(), -1, &stmt_, nullptr);
  if (rc != SQLITE_OK) db.fail(rc, "prepare");
}

Statement::~Statement() { sqlite3_finalize(stmt_); }

Statement& Statement::bind(int index, double value) {
  const int rc = sqlite3_bind_double(stmt_, index, value);
  if (rc != SQLITE_OK) db_.fail(rc, "bind");
  return *this;
}

Statement& Statement::bind(int index, std::int64_t value) {
  const int rc = sqlite3_bind_int64(stmt_, index, value);
  if (rc != SQLITE_OK) db_.fail(rc, "bind");
  return *this;
}

Statement& Statement::bind(int index, const std::string& value) {
  const int rc = sqlite3_bind_text(stmt_, index, value.data(), static_cast<int>(value.size()),
                                   SQLITE_TRANSIENT);
  if (rc != SQLITE_OK) db_.fail(rc, "bind");
  return *this;
}

Statement& Statement::bindBlob(int index, const std::vector<std::uint8_t>& bytes) {
  // NOTE: an empty vector still binds a zero-length blob, not NULL.
  static const std::uint8_t kEmpty = 0;
  const int rc = sqlite3_bind_blob(stmt_, index, bytes.empty() ? &kEmpty : bytes.data(),
                                   static_cast<int>(bytes.size()), SQLITE_TRANSIENT);
  if (rc != SQLITE_OK) db_.fail(rc, "bind");
  return *this;
}

Statement& Statement::bindNull(int index) {
  const int rc = sqlite3_bind_null(stmt_, index);
  if (rc != SQLITE_OK) db_.fail(rc, "bind");
  return *this;
}

bool Statement::step() {
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  sqlite3_reset(stmt_);
  db_.fail(rc, "step");
}

void Statement::run() {
  while (step()) {
  }
  reset();
}

void Statement::reset() {
  sqlite3_reset(stmt_);
  sqlite3_clear_bindings(stmt_);
}

bool Statement::isNull(int column) const {
  return sqlite3_column_type(stmt_, column) == SQLITE_NULL;
}
double Statement::getDouble(int column) const { return sqlite3_column_double(stmt_, column); }
std::int64_t Statement::getInt(int column) const { return sqlite3_column_int64(stmt_, column); }

std::string Statement::getText(int column) const {
  const auto* text = sqlite3_column_text(stmt_, column);
  return text ? std::string(reinterpret_cast<const char*>(text),
                            static_cast<std::size_t>(sqlite3_column_bytes(stmt_, column)))
              : std::string();
}

std::vector<std::uint8_t> Statement::getBlob(int column) const {
  const auto* data = static_cast<const std::uint8_t*>(sqlite3_column_blob(stmt_, column));
  const int size = sqlite3_column_bytes(stmt_, column);
  return data ? std::vector<std::uint8_t>(data, data + size) : std::vector<std::uint8_t>();
}

Transaction::Transaction(Database& db) : db_(db), depth_(db.transactionDepth()) {
  db_.exec(depth_ == 0 ? "BEGIN IMMEDIATE" : "SAVEPOINT nested", "begin transaction");
  ++db_.transactionDepth();
}

Transaction::~Transaction() {
  if (done_) return;
  --db_.transactionDepth();
  // Failures here are ignored: SQLite has already rolled back when a statement failed hard (full
  // disk, I/O error), and a destructor must not throw.
  if (depth_ == 0) {
    sqlite3_exec(db_.handle(), "ROLLBACK", nullptr, nullptr, nullptr);
  } else {
    sqlite3_exec(db_.handle(), "ROLLBACK TO nested; RELEASE nested", nullptr, nullptr, nullptr);
  }
}

void Transaction::commit() {
  db_.exec(depth_ == 0 ? "COMMIT" : "RELEASE nested", "commit");
  done_ = true;
  --db_.transactionDepth();
}

}  // namespace strata::store
