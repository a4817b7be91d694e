#pragma once
// How fast a flown path leaves a dead end: a region (a corridor closed at one end, as a box from
// above) the robot enters, follows to its deepest point and must leave the way it came.
//
// Depth of a position: its distance (x, y) from the mouth, where the dead end opens (by default
// the point of the region nearest the start; a start inside the dead end needs it given). The first
// visit: from the first position inside the region to the first position outside it after that.
// Escape time: from reaching the deepest point of that visit (where the dead end is used up) to
// leaving the region. Times are simulated seconds of the flown samples. Thread safety: a plain
// function.
#include <Eigen/Geometry>
#include <optional>
#include <vector>

namespace strata::explore {

struct DeadEndEscape {
  bool entered = false;
  double entered_s = 0.0;
  double deepest_s = 0.0;  // when the first visit reached its deepest point
  float deepest_m = 0.0f;  // how deep (metres from the mouth)
  /// When the robot left the region after its first visit; nullopt: still inside at the end.
  std::optional<double> left_s;
  /// left_s - deepest_s; nullopt when the robot never left.
  std::optional<double> escape_s;
  /// Simulated time after the deepest point until the run ended (a lower bound of the escape
  /// time of a run that never left).
  double after_deepest_s = 0.0;
};

/// A dead end from above (world x, y; metres).
struct DeadEnd {
  Eigen::AlignedBox2f region_xy;
  Eigen::Vector2f mouth_xy = Eigen::Vector2f::Zero();  // where it opens; depth counts from here
};

/// The dead end `region_xy` opening at its point nearest `start_W` (a start outside it).
DeadEnd deadEndSeenFrom(const Eigen::AlignedBox2f& region_xy, const Eigen::Vector3f& start_W);

/// `times_s[i]` is when the robot was at `positions_W[i]` (same length, increasing); the run
/// ended at `end_time_s`. InputError when the lengths differ or the region is empty.
DeadEndEscape analyseDeadEnd(const std::vector<double>& times_s,
                             const std::vector<Eigen::Vector3f>& positions_W,
                             const DeadEnd& dead_end, double end_time_s);

}  // namespace strata::explore
