#pragma once
// A thin RAII layer over SQLite's C API: a connection, prepared statements and transactions. Every
// failing call throws strata::Error (strata::InputError for a file that is not a usable database)
// naming the database file, the step and SQLite's own message.
// Thread safety: a Database and its Statements belong to one thread at a time.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

struct sqlite3;
struct sqlite3_stmt;

namespace strata::store {

class Database {
 public:
  /// Opens (create = true: creates when absent; read_only: for reading only, never creating) the
  /// SQLite file at `path`. The folder of a file to create must exist. InputError naming the path
  /// and SQLite's message when it cannot.
  Database(const std::string& path, bool create, bool read_only = false);
  ~Database();
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  const std::string& path() const { return path_; }
  sqlite3* handle() const { return db_; }

  /// Runs one or more statements without results (schema, pragmas).
  void exec(const std::string& sql, const char* step);
  /// Runs a statement returning one integer (PRAGMA user_version, COUNT(*)).
  std::int64_t queryInt(const std::string& sql, const char* step);
  /// Rows changed by the last INSERT / UPDATE / DELETE.
  std::int64_t changes() const;
  /// Row id of the last INSERT.
  std::int64_t lastInsertId() const;
  /// Throws the error for SQLite result code `rc` of `step` (never returns).
  [[noreturn]] void fail(int rc, const char* step) const;

  /// Nesting depth of the open Transaction objects (0: none).
  int& transactionDepth() { return transaction_depth_; }

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
  int transaction_depth_ = 0;
};

/// A prepared statement: bind (1-based indices, as in SQLite), step, read columns (0-based).
class Statement {
 public:
  Statement(Database& db, const std::string& sql);
  ~Statement();
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& bind(int index, double value);
  Statement& bind(int index, std::int64_t value);
  Statement& bind(int index, const std::string& value);
  Statement& bindBlob(int index, const std::vector<std::uint8_t>& bytes);
  Statement& bindNull(int index);
  template <typename T>
  Statement& bind(int index, const std::optional<T>& value) {
    return value ? bind(index, *value) : bindNull(index);
  }

  /// true while a row is available; false when done. Throws on error.
  bool step();
  /// Runs a statement without results to its end, then resets it for the next bindings.
  void run();
  /// Clears bindings and rewinds.
  void reset();

  bool isNull(int column) const;
  double getDouble(int column) const;
  std::int64_t getInt(int column) const;
  std::string getText(int column) const;
  std::vector<std::uint8_t> getBlob(int column) const;

 private:
  Database& db_;
  sqlite3_stmt* stmt_ = nullptr;
};

/// One transaction: the outermost begins an IMMEDIATE transaction (the write lock is taken up
/// front, so two writers never deadlock halfway), nested ones are savepoints. Destroyed without
/// commit() (an exception unwinding), it rolls back everything since it began.
class Transaction {
 public:
  explicit Transaction(Database& db);
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  /// Makes the changes durable (outermost) or merges them into the enclosing transaction.
  void commit();

 private:
  Database& db_;
  bool done_ = false;
  int depth_;
};

}  // namespace strata::store
