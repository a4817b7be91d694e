// The occupancy update rule; mirrors engine/kernels/occupancy_rules.h (see there for the why).
const uint kOccupancyMissThisScan = 1u;
const uint kOccupancyHitThisScan = 2u;
const uint kOccupancyObserved = 4u;
const uint kOccupancyScanBits = 3u;

// One update per voxel per scan, hit over miss. Eq. (2) of Hornung et al. 2013, clamped, Eq. (3).
float occupancyUpdate(uint state, float log_odds, float l_hit, float l_miss, float l_min,
                      float l_max) {
  if ((state & kOccupancyScanBits) == 0u) return log_odds;
  precise float previous = (state & kOccupancyObserved) != 0u ? log_odds : 0.0;
  precise float sum = previous + ((state & kOccupancyHitThisScan) != 0u ? l_hit : l_miss);
  return min(max(sum, l_min), l_max);
}

uint occupancyStateAfterUpdate(uint state) {
  return (state & kOccupancyScanBits) != 0u ? kOccupancyObserved : state;
}
