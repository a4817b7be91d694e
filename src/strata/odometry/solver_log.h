#pragma once
// The solver's own log. Ceres reports through glog, which writes to stderr by default (and, once
// initialised, to files in /tmp): raw lines a user of a Strata program cannot act on, in the
// middle of its messages. SolverLog routes them instead: counted, the first kept for the
// program's own message, and on stderr only when asked for (a program's --solver-log).
// Thread safety: install() once from main before any solver runs; the counts may be read from
// any thread (glog calls the sink under its own lock).
#include <cstddef>
#include <string>

namespace strata::odometry {

class SolverLog {
 public:
  /// Takes over glog for the whole process: no log files, nothing on stderr below FATAL unless
  /// `to_stderr`, every message (INFO and up) counted. `program` names the process in glog's
  /// lines. Calling it again only changes `to_stderr`.
  static SolverLog& install(const char* program, bool to_stderr);

  /// Messages the solver logged since install(), and the first of them ("" before one).
  std::size_t messages() const;
  std::string first() const;
  /// One line for the program's output when the solver logged anything, else "".
  std::string summary() const;

 private:
  SolverLog() = default;
};

}  // namespace strata::odometry
