#include "strata/core/progress.h"

#include <unistd.h>

#include <cstdio>

namespace strata {

ProgressBar::ProgressBar(std::string label, std::size_t total, bool enabled)
    : label_(std::move(label)),
      total_(total),
      enabled_(enabled),
      tty_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()) {}

void ProgressBar::update(std::size_t done, const std::string& detail) {
  if (!enabled_ || total_ == 0) return;
  const double fraction = static_cast<double>(done) / static_cast<double>(total_);
  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta_s = done > 0 ? elapsed_s * (1.0 - fraction) / fraction : 0.0;
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    std::fprintf(stderr, "\r%s [%.*s%*s] %zu/%zu %3.0f%% eta %.0fs %s\033[K", label_.c_str(),
                 filled, "==============================", kWidth - filled, "", done, total_,
                 fraction * 100.0, eta_s, detail.c_str());
    std::fflush(stderr);
    return;
  }
  const int decile = static_cast<int>(fraction * 10.0);
  if (decile != last_decile_) {
    last_decile_ = decile;
    std::fprintf(stderr, "%s %zu/%zu (%.0f%%) %s\n", label_.c_str(), done, total_,
                 fraction * 100.0, detail.c_str());
  }
}

void ProgressBar::finish() {
  if (!enabled_ || finished_) return;
  finished_ = true;
  if (tty_) std::fprintf(stderr, "\n");
}

}  // namespace strata
