#include "machine_info.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <thread>

namespace strata::bench {
namespace {

constexpr double kBytesPerMiB = 1024.0 * 1024.0;

std::string cpuModel() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) != 0) continue;
    const auto colon = line.find(':');
    if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
  }
  return "unknown";
}

std::string dateUtc() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

/// First line of a shell command's stdout ("" when it fails).
std::string commandLine(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return {};
  std::array<char, 256> buffer{};
  std::string line;
  if (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) line = buffer.data();
  const int status = pclose(pipe);
  if (status != 0) return {};
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
  return line;
}

/// HEAD of the source tree at run time, "-dirty" when tracked files differ; "unknown" without git.
std::string gitCommit() {
  const std::string git = std::string("git -C '") + STRATA_SOURCE_DIR + "' ";
  const std::string head = commandLine(git + "rev-parse HEAD 2>/dev/null");
  if (head.empty()) return "unknown";
  const std::string changes =
      commandLine(git + "status --porcelain --untracked-files=no 2>/dev/null");
  return changes.empty() ? head : head + "-dirty";
}

}  // namespace

std::string loadAverage() {
  std::ifstream file("/proc/loadavg");
  double one = 0, five = 0, fifteen = 0;
  if (!(file >> one >> five >> fifteen)) return "unknown";
  char text[64];
  std::snprintf(text, sizeof(text), "%.2f %.2f %.2f", one, five, fifteen);
  return text;
}

double peakRssMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double peak = static_cast<double>(usage.ru_maxrss) * 1024.0 / kBytesPerMiB;  // KiB
  // NOTE: the kernel updates the high-water mark lazily; it can trail the current RSS slightly.
  return std::max(peak, currentRssMiB());
}

double currentRssMiB() {
  std::ifstream statm("/proc/self/statm");
  long pages_total = 0, pages_resident = 0;
  if (!(statm >> pages_total >> pages_resident)) return 0.0;
  return static_cast<double>(pages_resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) /
         kBytesPerMiB;
}

Json machineInfo(const std::string& device_name, const std::string& load_at_start) {
  const char* lp_threads = std::getenv("LP_NUM_THREADS");
  return Json::object()
      .set("cpu_model", cpuModel())
      .set("logical_cores", std::thread::hardware_concurrency())
      .set("device", device_name)
      .set("lp_num_threads", lp_threads != nullptr ? lp_threads : "unset")
      .set("date_utc", dateUtc())
      .set("git_commit", gitCommit())
      .set("build_type", std::string(STRATA_BUILD_TYPE).empty() ? "unset" : STRATA_BUILD_TYPE)
      .set("load_average_at_start", load_at_start)
      .set("load_average_at_end", loadAverage());
}

}  // namespace strata::bench
