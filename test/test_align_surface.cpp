// Place recognition and verification without texture (docs/align.md "Surface path"): surface
// descriptors from depth, FPFH RANSAC and dense ICP on the flat-shaded simulated office, where ORB
// finds corners only on edges.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <vector>

#include "strata/align/keyframe_features.h"
#include "strata/align/loop_verifier.h"
#include "strata/align/surface_descriptor.h"
#include "strata/core/error.h"
#include "strata/sim/session/sim_session.h"
#include "strata/sim/world/world_paths.h"
#include "test_utils.h"

namespace strata::align {
namespace {

// One rendered frame of the flat-shaded office with its features and surface.
struct View {
  RgbdFrame frame;
  KeyframeFeatures features;
  KeyframeSurface surface;
  Eigen::Isometry3d T_W_C;
};

class FlatOffice {
 public:
  explicit FlatOffice(int frames = 150) {
    const auto world =
        std::make_shared<const sim::World>(sim::World::load(sim::findWorld("office")));
    sim::SimSessionConfig config;
    config.max_frames = frames;  // 150: frames 0.3-0.4 m apart, as scripts/align-eval.sh renders
    session_ = std::make_unique<sim::SimSessionDataset>(world, 0, config);
  }
  View view(std::size_t i) const {
    View v;
    v.frame = session_->load(i);
    const CameraIntrinsics k = session_->intrinsics();
    v.features = extractFeatures(v.frame.color, v.frame.depth, k, {});
    v.surface = describeSurface(v.frame.depth, k, {});
    v.T_W_C = session_->truePoses()[i];
    return v;
  }
  CameraIntrinsics intrinsics() const { return session_->intrinsics(); }

 private:
  std::unique_ptr<sim::SimSessionDataset> session_;
};

double rotationErrorDeg(const Eigen::Isometry3d& A, const Eigen::Isometry3d& B) {
  return Eigen::AngleAxisd(A.linear().transpose() * B.linear()).angle() * 180.0 / M_PI;
}

VerifyKeyframe keyframe(const View& v, const CameraIntrinsics& k, bool with_surface) {
  return {&v.features, &v.frame.depth, k, with_surface ? &v.surface : nullptr};
}

TEST(SurfaceDescriptor, FlatShadedOfficeFrameHasKeypointsAndAGlobalDescriptor) {
  const FlatOffice office;
  const View v = office.view(20);
  // Measured: 500 keypoints (the cap), a 65-value descriptor (33 FPFH + 16 D2 + 16 ranges).
  EXPECT_GE(v.surface.size(), 100u);
  EXPECT_EQ(v.surface.fpfh.size(), v.surface.size());
  EXPECT_EQ(v.surface.global.size(), 65u);
  EXPECT_EQ(surfaceDistance(v.surface, v.surface), 0.0);
  EXPECT_THROW(describeSurface(DepthImage(320, 240), office.intrinsics(), {}), InputError);
  SurfaceConfig bad;
  bad.fpfh_radius_m = 0.05f;  // not wider than the normals' radius
  EXPECT_THROW(describeSurface(v.frame.depth, office.intrinsics(), bad), InputError);
}

// Consecutive frames of 300 spread over the office path, 0.15-0.2 m and up to tens of degrees
// apart: where ORB on the flat shading finds too few matches, the surface path measures the pair.
TEST(SurfaceVerification, FlatShadedPairsTheOrbPathMissesAreMeasuredBySurface) {
  const FlatOffice office(300);
  const CameraIntrinsics k = office.intrinsics();
  int pairs = 0, orb_accepted = 0, surface_accepted = 0, surface_only = 0;
  double worst_m = 0.0, worst_deg = 0.0;
  for (std::size_t i = 8; i < 300; i += 30) {
    const View a = office.view(i), b = office.view(i + 1);
    const LoopMeasurement orb = verifyLoop(keyframe(a, k, false), keyframe(b, k, false));
    const LoopMeasurement both = verifyLoop(keyframe(a, k, true), keyframe(b, k, true));
    ++pairs;
    orb_accepted += orb.accepted;
    if (!both.accepted) {
      std::cout << i << ": " << both.reason << "\n";
      continue;
    }
    const Eigen::Isometry3d truth = a.T_W_C.inverse() * b.T_W_C;
    const double error_m = (both.T_a_b.translation() - truth.translation()).norm();
    const double error_deg = rotationErrorDeg(both.T_a_b, truth);
    worst_m = std::max(worst_m, error_m);
    worst_deg = std::max(worst_deg, error_deg);
    EXPECT_LT(error_m, 0.02) << i;
    EXPECT_LT(error_deg, 1.0) << i;
    if (both.from_surface) {
      ++surface_accepted;
      surface_only += !orb.accepted;
    }
  }
  std::cout << "flat office, " << pairs << " consecutive pairs: ORB accepted " << orb_accepted
            << ", surface path accepted " << surface_accepted << " (" << surface_only
            << " that ORB missed); worst error " << worst_m * 1e3 << " mm, " << worst_deg
            << " deg\n";
  // Measured 2026-12-07: ORB accepted 1 of 10, the surface path 2 that ORB missed, worst error
  // 3.8 mm and 0.10 deg (bounds above: 2 cm, 1 deg).
  EXPECT_GE(surface_only, 2);
}

// Frames of different rooms (true camera positions over 4 m apart): the surface path may find
// FPFH correspondences, but no candidate passes RANSAC, ICP and its gates.
TEST(SurfaceVerification, RefusesFlatShadedPairsOfDifferentPlaces) {
  const FlatOffice office;
  const CameraIntrinsics k = office.intrinsics();
  std::vector<View> views;
  for (std::size_t i = 10; i < 150; i += 15) views.push_back(office.view(i));
  int tried = 0, accepted = 0;
  for (std::size_t x = 0; x < views.size(); ++x) {
    for (std::size_t y = x + 1; y < views.size(); ++y) {
      const View& a = views[x];
      const View& b = views[y];
      if ((a.T_W_C.translation() - b.T_W_C.translation()).norm() < 4.0) continue;
      const LoopMeasurement m = verifyLoop(keyframe(a, k, true), keyframe(b, k, true));
      ++tried;
      accepted += m.accepted;
      EXPECT_FALSE(m.accepted) << x << "-" << y;
      EXPECT_FALSE(m.reason.empty());
    }
  }
  std::cout << "flat office, pairs over 4 m apart: " << accepted << " of " << tried
            << " accepted\n";
  EXPECT_GE(tried, 10);  // measured: 0 of 27 accepted
}

}  // namespace
}  // namespace strata::align
