#pragma once
// A progress bar for long work: redrawn in place on a terminal, a line every 10 % otherwise (logs).
#include <chrono>
#include <cstddef>
#include <string>

namespace strata {

class ProgressBar {
 public:
  ProgressBar(std::string label, std::size_t total, bool enabled = true);
  /// `done` items finished; `detail` is shown after the bar (e.g. "12.3 ms/frame").
  void update(std::size_t done, const std::string& detail = {});
  /// Ends the bar's line.
  void finish();

 private:
  std::string label_;
  std::size_t total_;
  bool enabled_;
  bool tty_;
  int last_decile_ = -1;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace strata
