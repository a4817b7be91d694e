// Aligns the sessions of a map database (`strata map import` writes one) in place: place
// recognition and verified loops between the sessions' keyframes, then a pose graph; each
// session's pose in the world frame (the first session's) goes back into the store and is printed.
//   align_sessions MAP.sqlite
#include <cstdio>
#include <exception>

#include "strata/align/store_alignment.h"
#include "strata/io/tum_format.h"
#include "strata/store/session_store.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: align_sessions MAP.sqlite\n");
    return 2;
  }
  try {
    strata::store::StoreOptions options;
    options.create = false;  // a missing file is an error, not a new empty map
    strata::store::Store store(argv[1], options);
    const auto progress = [](const std::string& stage, std::size_t done, std::size_t total) {
      if (done == total) std::fprintf(stderr, "%s: %zu done\n", stage.c_str(), total);
    };
    const strata::align::StoreAlignment alignment = strata::align::alignStore(store, {}, progress);
    std::size_t accepted = 0;
    for (const strata::align::AlignLoop& loop : alignment.result.loops) accepted += loop.accepted;
    std::printf("%zu loops verified, %zu kept by the pose graph\n", alignment.result.loops.size(),
                accepted);
    // What the store now holds: T_W_S (session to world) of every aligned session.
    for (const strata::store::SessionRecord& s : store.sessions()) {
      if (s.T_W_S) {
        std::printf("session %lld '%s': T_W_S = %s (tx ty tz qx qy qz qw)\n",
                    static_cast<long long>(s.id), s.name.c_str(),
                    strata::tum::poseToTum(*s.T_W_S).c_str());
      } else {
        std::printf("session %lld '%s': not aligned (no verified loop joins it)\n",
                    static_cast<long long>(s.id), s.name.c_str());
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "align_sessions: %s\n", e.what());
    return 1;
  }
  return 0;
}
