#pragma once
// Bad input, counted per channel and logged with the channel and the reason. Logging is limited
// (the first kLoggedPerChannel per channel, then every kLogEvery-th) so a flood of garbage cannot
// flood the log too.
// Thread safety: thread safe.
#include <cstdint>
#include <map>
#include <mutex>
#include <string>

namespace strata::lcm_io {

class InputStats {
 public:
  static constexpr std::int64_t kLoggedPerChannel = 10;
  static constexpr std::int64_t kLogEvery = 1000;

  /// `log_prefix` starts every log line (the process name).
  explicit InputStats(std::string log_prefix, bool log = true);

  void countBad(const std::string& channel, const std::string& reason);
  std::int64_t totalBad() const;
  std::map<std::string, std::int64_t> badByChannel() const;

 private:
  std::string prefix_;
  bool log_;
  mutable std::mutex mutex_;
  std::map<std::string, std::int64_t> bad_;
  std::int64_t total_ = 0;
};

}  // namespace strata::lcm_io
