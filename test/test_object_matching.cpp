// Matching objects of any shape (registration level, no device): partial views of procedural
// shapes from other sides, a different shape of similar size, and a near-square box turned a
// quarter, whose true pose the registration keeps among its alternatives
// (RegistrationConfig::yaw_alternatives) for the object database's volumetric check to choose.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <tuple>

#include "strata/objects/object_registration.h"
#include "surface_cells.h"
#include "strata/sim/world/procedural_shapes.h"
#include "strata/sim/world/shape_mesh.h"

namespace strata::objects {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kVoxel = 0.02f;

sim::ShapeSpec shape(sim::ShapeKind kind, const Eigen::Vector3d& size_m, std::uint64_t seed = 1) {
  sim::ShapeSpec s;
  s.kind = kind;
  s.size_m = size_m;
  s.seed = seed;
  return s;
}

/// World-frame samples (one per voxel cube, 2 mm noise) of the faces of the shape at T_W_P that
/// look towards the views (azimuths in degrees, elevation 35 deg) and not down.
test::SurfaceCells samples(
    const sim::ShapeSpec& spec, const Eigen::Isometry3d& T_W_P,
    const std::vector<double>& azimuths_deg, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::normal_distribution<float> noise(0.0f, 0.002f);
  test::SurfaceCells cells;
  const Eigen::Isometry3f T = T_W_P.cast<float>();
  const double el = 35.0 * kPi / 180.0;
  for (const double azimuth_deg : azimuths_deg) {
    const double az = azimuth_deg * kPi / 180.0;
    const Eigen::Vector3f to_camera(static_cast<float>(std::cos(el) * std::cos(az)),
                                    static_cast<float>(std::cos(el) * std::sin(az)),
                                    static_cast<float>(std::sin(el)));
    for (const Mesh& part : sim::shapeParts(spec)) {
      for (const Eigen::Vector3i& tri : part.triangles) {
        const Eigen::Vector3f a = T * part.vertices[tri[0]], b = T * part.vertices[tri[1]],
                              c = T * part.vertices[tri[2]];
        const Eigen::Vector3f cross = (b - a).cross(c - a);
        if (cross.norm() < 1e-12f) continue;
        const Eigen::Vector3f n = cross.normalized();
        if (n.dot(to_camera) < 0.1f || n.z() < -0.5f) continue;
        const int count = static_cast<int>(0.5f * cross.norm() / (0.25f * kVoxel * kVoxel)) + 1;
        for (int i = 0; i < count; ++i) {
          float u = unit(rng), v = unit(rng);
          if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
          const Eigen::Vector3f p =
              a + u * (b - a) + v * (c - a) + Eigen::Vector3f(noise(rng), noise(rng), noise(rng));
          const Eigen::Vector3i cell = (p / kVoxel).array().floor().cast<int>();
          cells.emplace(std::make_tuple(cell.x(), cell.y(), cell.z()), std::make_pair(p, n));
        }
      }
    }
  }
  return cells;
}

/// The shape at T_W_P seen from `azimuths_deg` as one cloud in the frame O at its centroid (axes
/// as the world's, as observations are); returns the cloud and T_W_O.
std::pair<SurfaceCloud, Eigen::Isometry3d> view(const sim::ShapeSpec& spec,
                                                const Eigen::Isometry3d& T_W_P,
                                                const std::vector<double>& azimuths_deg,
                                                unsigned seed) {
  const auto cells = samples(spec, T_W_P, azimuths_deg, seed);
  return test::cloudAboutCentroid(cells);
}

RegistrationConfig config() {
  RegistrationConfig c;
  c.voxel_size_m = kVoxel;
  return c;
}

/// Translation (at the source's origin) and rotation error of `estimate` against `truth`, the
/// rotation modulo `order`-fold yaw symmetry of the shape (1: none).
std::pair<double, double> errors(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth,
                                 const Eigen::Isometry3d& T_P_target, int order) {
  double best_t = 1e9, best_r = 1e9;
  for (int k = 0; k < order; ++k) {
    // A symmetry of the shape, in the target's frame.
    const Eigen::Isometry3d S =
        T_P_target.inverse() * sim::floorPose(Eigen::Vector2d::Zero(), 360.0 * k / order) *
        T_P_target;
    const Eigen::Isometry3d delta = (S * truth).inverse() * estimate;
    const double t = delta.translation().norm();
    if (t < best_t) {
      best_t = t;
      best_r = Eigen::AngleAxisd(delta.rotation()).angle() * 180.0 / kPi;
    }
  }
  return {best_t, best_r};
}

struct Case {
  RegistrationResult result;
  Eigen::Isometry3d truth;       // T_target_source
  Eigen::Isometry3d T_P_target;  // the target's frame in the object's
};

/// Model: the object at the origin seen from `model_azimuths`; observation: the object moved by
/// `yaw_deg` and (1.4, -0.7) m, seen from `view_azimuth` (relative to the moved object).
Case registerViews(const sim::ShapeSpec& model_spec, const sim::ShapeSpec& seen_spec,
                   const std::vector<double>& model_azimuths, double view_azimuth, double yaw_deg) {
  const Eigen::Isometry3d T_W_P1 = sim::floorPose(Eigen::Vector2d(0.0, 0.0), 0.0);
  const Eigen::Isometry3d T_W_P2 = sim::floorPose(Eigen::Vector2d(1.4, -0.7), yaw_deg);
  const auto [target, T_W_Ot] = view(model_spec, T_W_P1, model_azimuths, 1);
  const auto [source, T_W_Os] = view(seen_spec, T_W_P2, {view_azimuth + yaw_deg}, 2);
  Case c;
  c.result = registerSurfaces(source, target, config());
  c.truth = T_W_Ot.inverse() * T_W_P1 * T_W_P2.inverse() * T_W_Os;
  c.T_P_target = T_W_P1.inverse() * T_W_Ot;
  return c;
}

/// The best pose's errors and the nearest of the best and its alternatives to the truth.
struct Found {
  double best_t, best_r, nearest_t, nearest_r;
};
Found found(const Case& c, int order) {
  const auto [t, r] = errors(c.result.T_target_source, c.truth, c.T_P_target, order);
  Found f{t, r, t, r};
  for (const PoseAlternative& a : c.result.alternatives) {
    const auto [at, ar] = errors(a.T_target_source, c.truth, c.T_P_target, order);
    if (at < f.nearest_t) f.nearest_t = at, f.nearest_r = ar;
  }
  return f;
}

// A model seen from two sides and a later view from a third (110 deg from the nearer: they share
// the top and part of one side). The blob and the tube have no symmetry and come back within
// 1 cm / 2 deg as the best pose (measured 2.7 mm / 0.31 deg and 2.2 mm / 0.28 deg). The L block
// seen from its outer corner fits its inner corner's side turned a half (measured: best 0.34 m /
// 180 deg at fitness 0.665), and the true pose is its alternative (6.1 mm / 0.03 deg), for the
// database's volumetric check to choose.
TEST(ObjectMatching, PartialViewOfAProceduralShapeFromAnotherSideRegisters) {
  const sim::ShapeSpec blob = shape(sim::ShapeKind::kBlob, {0.55, 0.45, 0.45}, 3);
  const sim::ShapeSpec tube = shape(sim::ShapeKind::kTube, {0.7, 0.6, 0.55}, 5);
  const sim::ShapeSpec l_block = shape(sim::ShapeKind::kLShape, {0.8, 0.6, 0.6});
  for (const sim::ShapeSpec* spec : {&blob, &tube, &l_block}) {
    const char* name = sim::shapeKindName(spec->kind);
    const Case c = registerViews(*spec, *spec, {0.0, 110.0}, 220.0, 65.0);
    ASSERT_TRUE(c.result.converged) << name << ": " << c.result.reason;
    const Found f = found(c, 1);
    std::printf("%s: fitness %.3f, coverage %.3f, best %.4f m %.2f deg, %zu alternatives, the "
                "nearest %.4f m %.2f deg\n",
                name, c.result.fitness, c.result.target_coverage, f.best_t, f.best_r,
                c.result.alternatives.size(), f.nearest_t, f.nearest_r);
    if (spec != &l_block) {
      EXPECT_LT(f.best_t, 0.01) << name;
      EXPECT_LT(f.best_r, 2.0) << name;
    }
    EXPECT_LT(f.nearest_t, 0.01) << name;
    EXPECT_LT(f.nearest_r, 2.0) << name;
  }
}

// A vase's view, and another seed's blob, registered onto a blob's model of about the same size
// fit far worse than a view of the blob itself (measured: the blob's own view fitness 1.000, the
// other two find no upright RANSAC hypothesis at all): the figure the database's score starts
// from. Bound: below 0.75 of the right fitness.
TEST(ObjectMatching, ADifferentShapeOfSimilarSizeFitsBadly) {
  const sim::ShapeSpec blob = shape(sim::ShapeKind::kBlob, {0.5, 0.5, 0.5}, 4);
  const sim::ShapeSpec vase = shape(sim::ShapeKind::kVase, {0.45, 0.45, 0.5}, 1);
  const sim::ShapeSpec other_blob = shape(sim::ShapeKind::kBlob, {0.5, 0.5, 0.5}, 9);
  const Case right = registerViews(blob, blob, {0.0, 110.0}, 60.0, 40.0);
  ASSERT_TRUE(right.result.converged) << right.result.reason;
  for (const sim::ShapeSpec* spec : {&vase, &other_blob}) {
    const Case wrong = registerViews(blob, *spec, {0.0, 110.0}, 60.0, 40.0);
    std::printf("same blob fitness %.3f; %s (seed %llu) onto it: converged %d, fitness %.3f\n",
                right.result.fitness, sim::shapeKindName(spec->kind),
                static_cast<unsigned long long>(spec->seed), wrong.result.converged,
                wrong.result.fitness);
    EXPECT_TRUE(!wrong.result.converged || wrong.result.fitness < 0.75 * right.result.fitness);
  }
}

// A 0.5 x 0.44 m box turned a quarter and seen from one corner: its two faces fit the model's
// (seen from two other corners) turned a quarter nearly as well as in place. The true pose
// (modulo the box's half turn) is the best or one of the alternatives (measured: the best,
// within 0.4 mm / 0.2 deg, with 3 alternatives, the quarter turns).
TEST(ObjectMatching, NearSquareBoxTurnedAQuarterKeepsTheTruePoseAmongItsHypotheses) {
  const sim::ShapeSpec box = shape(sim::ShapeKind::kBox, {0.5, 0.44, 0.35});
  for (const double yaw_deg : {100.0, 275.0}) {
    const Case c = registerViews(box, box, {30.0, 210.0}, 60.0, yaw_deg);
    ASSERT_TRUE(c.result.converged) << c.result.reason;
    const Found f = found(c, 2);
    std::printf("box turned %.0f deg: best %.4f m %.2f deg (fitness %.3f); %zu alternatives, "
                "the nearest %.4f m %.2f deg\n",
                yaw_deg, f.best_t, f.best_r, c.result.fitness, c.result.alternatives.size(),
                f.nearest_t, f.nearest_r);
    EXPECT_LT(f.nearest_t, 0.01) << yaw_deg;
    EXPECT_LT(f.nearest_r, 2.0) << yaw_deg;
    // The quarter turns are offered: two at least (a quarter each way) besides the best.
    EXPECT_GE(c.result.alternatives.size(), 2u) << yaw_deg;
  }
}

}  // namespace
}  // namespace strata::objects
