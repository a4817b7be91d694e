// RGB-D tracking on real data: the redkitchen sample fused without its poses (the first frame
// keeps its pose), the estimated trajectory against the dataset's poses.
#include <gtest/gtest.h>

#include <cstdio>

#include "fusion_fixture.h"
#include "strata/io/open_dataset.h"
#include "strata/mapper/mapper.h"
#include "test_utils.h"
#include "strata/trajectory/trajectory_error.h"

namespace strata {
namespace {

TEST(TrackRedkitchen, TracksWithoutPosesWithinThreeCentimetres) {
  STRATA_REQUIRE_DATA("redkitchen", folder);
  const std::unique_ptr<Dataset> dataset = openDataset(folder);
  // NOTE: 60 frames (2 s of the sequence) keep the run near a minute on 2 shared cores.
  const std::size_t frames = std::min<std::size_t>(60, dataset->size());
  Mapper mapper(MapperConfig{}, test::sharedContext());
  std::vector<trajectory::StampedPose> estimate, truth;
  std::size_t lost = 0;
  for (std::size_t i = 0; i < frames; ++i) {
    const RgbdFrame frame = dataset->load(i);
    const TrackedFrame tracked = mapper.trackAndIntegrate(frame, dataset->intrinsics());
    if (!tracked.fused) {
      ++lost;
      continue;
    }
    estimate.push_back({frame.timestamp_s, tracked.track.T_W_C});
    truth.push_back({frame.timestamp_s, frame.T_W_C});
  }
  const trajectory::TrajectoryError error =
      trajectory::evaluateTrajectory(estimate, truth, trajectory::Alignment::kSE3);
  std::printf("redkitchen %zu frames: %zu lost, ATE RMSE %.1f mm, max %.1f mm, path %.2f m\n",
              frames, lost, error.ate_rmse_m * 1e3, error.ate_max_m * 1e3, error.path_length_m);
  EXPECT_EQ(lost, 0u);
  EXPECT_EQ(error.matched, frames - lost);
  EXPECT_LE(error.ate_rmse_m, 0.03);
}

}  // namespace
}  // namespace strata
