#include "strata/odometry/solver_log.h"

#include <glog/logging.h>

#include <mutex>

namespace strata::odometry {
namespace {

class CountingSink final : public google::LogSink {
 public:
  using google::LogSink::send;  // the other overload glog keeps for compatibility
  void send(google::LogSeverity, const char*, const char* base_filename, int line,
            const google::LogMessageTime&, const char* message, std::size_t message_len) override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (count_++ == 0) {
      first_ = std::string(base_filename) + ":" + std::to_string(line) + ": " +
               std::string(message, message_len);
    }
  }
  std::size_t count() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return count_;
  }
  std::string first() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return first_;
  }

 private:
  mutable std::mutex mutex_;
  std::size_t count_ = 0;
  std::string first_;
};

CountingSink& sink() {
  static CountingSink instance;
  return instance;
}

}  // namespace

SolverLog& SolverLog::install(const char* program, bool to_stderr) {
  static SolverLog log;
  static std::once_flag once;
  std::call_once(once, [program] {
    google::InitGoogleLogging(program);
    for (const google::LogSeverity severity :
         {google::GLOG_INFO, google::GLOG_WARNING, google::GLOG_ERROR, google::GLOG_FATAL}) {
      google::SetLogDestination(severity, "");  // "": no log file
    }
    FLAGS_logtostderr = false;
    FLAGS_alsologtostderr = false;
    google::AddLogSink(&sink());
  });
  FLAGS_stderrthreshold = to_stderr ? google::GLOG_INFO : google::GLOG_FATAL;
  return log;
}

std::size_t SolverLog::messages() const { return sink().count(); }

std::string SolverLog::first() const { return sink().first(); }

std::string SolverLog::summary() const {
  const std::size_t n = messages();
  if (n == 0) return "";
  std::string text = first();
  constexpr std::size_t kMaxQuoted = 200;
  if (text.size() > kMaxQuoted) text = text.substr(0, kMaxQuoted) + "...";
  for (char& c : text) {
    if (c == '\n') c = ' ';
  }
  return "the solver logged " + std::to_string(n) + " message" + (n == 1 ? "" : "s") +
         " (--solver-log shows them); the first: " + text;
}

}  // namespace strata::odometry
