#pragma once
// SIGKILL at random moments of a program's map save, many times over, checking after each kill
// that the map file is the previous one byte for byte or a complete new one (it loads: magic,
// version, sizes and CRC checked), and that killed writers' temporaries do not pile up.
#include <filesystem>
#include <string>
#include <vector>

namespace strata::test {

/// A program that writes `target` (atomically) at some point of its run.
struct SaveTrial {
  std::string program;
  /// Each run uses another variant than the one whose map the file holds: variants that save
  /// different maps make every completed save visible.
  std::vector<std::vector<std::string>> arg_variants;
  std::filesystem::path target;
  std::filesystem::path log;
  /// true: the program exits after its save (strata fuse); false: it keeps running until told
  /// (strata-mapper saving on command), and a SIGTERM ends it with one more save.
  bool exits_after_save = true;
  /// Every saved map differs from the one before (distinct variants); checked when true.
  bool saves_differ = true;
  double timeout_s = 120.0;
};

struct KillCounts {
  int before = 0, during = 0, after = 0;
  int most_temporaries = 0;  // `<name>.tmp.*` files present at once after a kill
};

/// First one run of variant 0 to its save, measuring when its temporary appears (T after the
/// start) and how long until the rename (W). Then `kills` runs, each killed (SIGKILL) at a random
/// moment: one in five at a uniform delay within [0, T] of its start (mostly before the write),
/// the others at a uniform delay within [0, W'] after their temporary appears, W' the median of
/// the write durations seen so far (most land during the write, some just after). Checks each kill with gtest expectations (and that some landed during
/// the write), prints the window and the counts, then runs variant 0 once to the end and checks
/// that its save removed every temporary left behind.
KillCounts killDuringSaves(const SaveTrial& trial, int kills, unsigned seed);

}  // namespace strata::test
