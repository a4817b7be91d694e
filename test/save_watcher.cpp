#include "save_watcher.h"

#include <poll.h>
#include <sys/inotify.h>
#include <unistd.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace strata::test {
namespace fs = std::filesystem;

const char* landingName(KillLanding landing) {
  switch (landing) {
    case KillLanding::kBefore:
      return "before";
    case KillLanding::kDuring:
      return "during";
    case KillLanding::kAfter:
      return "after";
  }
  return "?";
}

SaveWatcher::SaveWatcher(const fs::path& target) : target_(target) {
  fd_ = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
  if (fd_ < 0 || inotify_add_watch(fd_, target.parent_path().c_str(), IN_CREATE | IN_MOVED_TO) < 0) {
    throw std::runtime_error("inotify cannot watch " + target.parent_path().string());
  }
}

SaveWatcher::~SaveWatcher() {
  if (fd_ >= 0) close(fd_);
}

void SaveWatcher::reset() {
  poll(0.0);
  created_.reset();
  renamed_.reset();
}

void SaveWatcher::poll(double timeout_s) {
  pollfd p{fd_, POLLIN, 0};
  if (::poll(&p, 1, static_cast<int>(timeout_s * 1000.0)) <= 0) return;
  const Clock::time_point now = Clock::now();
  alignas(inotify_event) char buffer[16384];
  const std::string temporary_prefix = target_.filename().string() + ".tmp.";
  for (;;) {
    const ssize_t n = read(fd_, buffer, sizeof buffer);
    if (n <= 0) return;
    for (ssize_t at = 0; at < n;) {
      const auto* event = reinterpret_cast<const inotify_event*>(buffer + at);
      at += static_cast<ssize_t>(sizeof(inotify_event) + event->len);
      const std::string name = event->len ? event->name : "";
      if ((event->mask & IN_CREATE) && name.rfind(temporary_prefix, 0) == 0 && !created_) {
        created_ = now;
      }
      if ((event->mask & IN_MOVED_TO) && name == target_.filename().string() && !renamed_) {
        renamed_ = now;
      }
    }
  }
}

template <typename Seen>
bool SaveWatcher::waitFor(Seen seen, double timeout_s) {
  const Clock::time_point end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                   std::chrono::duration<double>(timeout_s));
  while (!seen()) {
    const double left_s = std::chrono::duration<double>(end - Clock::now()).count();
    if (left_s <= 0.0) return false;
    poll(std::min(left_s, 0.05));
  }
  return true;
}

void SaveWatcher::watchFor(double seconds) {
  waitFor([] { return false; }, seconds);
}

bool SaveWatcher::waitForTemporary(double timeout_s) {
  return waitFor([this] { return created_.has_value(); }, timeout_s);
}

bool SaveWatcher::waitForRename(double timeout_s) {
  return waitFor([this] { return renamed_.has_value(); }, timeout_s);
}

KillLanding SaveWatcher::landing() const {
  if (renamed_) return KillLanding::kAfter;
  return created_ ? KillLanding::kDuring : KillLanding::kBefore;
}

int SaveWatcher::temporariesPresent() const {
  const std::string prefix = target_.filename().string() + ".tmp.";
  int count = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(target_.parent_path())) {
    if (entry.path().filename().string().rfind(prefix, 0) == 0) ++count;
  }
  return count;
}

}  // namespace strata::test
