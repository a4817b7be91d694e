// The volumetric consistency check on constructed sessions (a box against itself, a box of
// another size, a cylinder, a taller box) and the size/colour prefilter.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

#include "strata/core/error.h"
#include "object_volume_scene.h"
#include "strata/objects/consistency_check.h"
#include "strata/objects/object_model.h"
#include "strata/objects/object_prefilter.h"

namespace strata::objects {
namespace {

using test::kVoxel;

const Eigen::AlignedBox3d kBox = test::footBox(0.4, 0.3, 0.4);
const auto kEverywhere = [](const Eigen::Vector3d&) { return true; };

struct Session {
  test::ObjectSession scene;
  ObjectObservation observation;
  Eigen::Isometry3d T_W_L;
};

Session observe(const test::Sdf& object_L, const Eigen::Isometry3d& T_W_L, int session) {
  Session s{
      test::makeObjectSession(test::placed(object_L, T_W_L), kEverywhere, session), {}, T_W_L};
  s.observation = observeObject(s.scene.map, s.scene.surface, test::onlyObject(s.scene), session);
  return s;
}

test::Sdf boxSdf(const Eigen::AlignedBox3d& box) {
  return [box](const Eigen::Vector3d& p) { return test::boxSdf(p, box); };
}

/// The model (founded in `model_session`) and the observation at the pose that puts their
/// frames L on each other.
Eigen::Isometry3d trueT_M_O(const Session& model_session, const Session& observed) {
  return model_session.observation.T_W_O.inverse() * model_session.T_W_L *
         observed.T_W_L.inverse() * observed.observation.T_W_O;
}

void print(const char* what, const ConsistencyResult& r) {
  std::cout << what << ": " << (r.accepted ? "accepted" : "refused") << ", agreement "
            << r.agreement << ", overlap " << r.overlap << " (" << r.compared_voxels << " of "
            << r.observation_surface_voxels << "), model agreement " << r.model_agreement << " ("
            << r.model_compared_voxels << "), free space " << r.free_space_violation << " ("
            << r.model_samples_in_free_space << " of " << r.model_samples_observed << ") "
            << r.reason << "\n";
}

class Consistency : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    model_session_ = new Session(observe(boxSdf(kBox), test::floorPose(0.8, 0.8, 0.0), 1));
    model_ = new ObjectModel(foundModel(1, model_session_->observation, ObjectModelConfig{}));
  }
  static void TearDownTestSuite() {
    delete model_;
    delete model_session_;
  }
  /// How far a result is from acceptance under the default config: the smallest margin of its
  /// four tests (negative: refused by that much).
  static double margin(const ConsistencyResult& r) {
    const ConsistencyConfig c;
    return std::min({r.agreement - c.min_agreement, r.model_agreement - c.min_agreement,
                     r.overlap - c.min_overlap,
                     c.max_free_space_violation - r.free_space_violation});
  }
  /// Over shifts of up to 4 voxels along x and y around the true pose: the result nearest to
  /// acceptance.
  static ConsistencyResult nearestToAcceptance(const Session& other) {
    ConsistencyResult best;
    double best_margin = -1e9;
    for (int dx = -4; dx <= 4; ++dx) {
      for (int dy = -4; dy <= 4; ++dy) {
        const Eigen::Isometry3d T_M_O =
            Eigen::Translation3d(dx * kVoxel, dy * kVoxel, 0.0) * trueT_M_O(*model_session_, other);
        const ConsistencyResult r =
            checkConsistency(*model_, other.observation, T_M_O, other.scene.map);
        if (margin(r) > best_margin) {
          best_margin = margin(r);
          best = r;
        }
      }
    }
    return best;
  }
  static Session* model_session_;
  static ObjectModel* model_;
};
Session* Consistency::model_session_ = nullptr;
ObjectModel* Consistency::model_ = nullptr;

TEST_F(Consistency, TheSameBoxAtItsTruePoseIsAccepted) {
  const Session other = observe(boxSdf(kBox), test::floorPose(0.75, 0.85, 0.35), 2);
  const ConsistencyResult r = checkConsistency(*model_, other.observation,
                                               trueT_M_O(*model_session_, other), other.scene.map);
  print("same box", r);
  EXPECT_TRUE(r.accepted) << r.reason;
  EXPECT_TRUE(r.reason.empty());
  EXPECT_GT(r.agreement, 0.9);
  EXPECT_GT(r.overlap, 0.8);
  EXPECT_LT(r.free_space_violation, 0.01);
  EXPECT_GT(r.model_samples_observed, model_->surface_M.size() / 2);
  // 6 cm off, the same box no longer agrees.
  const ConsistencyResult off = checkConsistency(
      *model_, other.observation,
      Eigen::Translation3d(0.06, 0.0, 0.0) * trueT_M_O(*model_session_, other), other.scene.map);
  print("same box, 6 cm off", off);
  EXPECT_FALSE(off.accepted);
}

TEST_F(Consistency, BoxesOfOtherSizesAreRefusedAtEveryNearbyPose) {
  // 10 % larger footprint; smaller on every side (that one also reaches the free space test).
  const Eigen::AlignedBox3d others[] = {test::footBox(0.44, 0.34, 0.4),
                                        test::footBox(0.32, 0.24, 0.3)};
  int session = 3;
  for (const auto& box : others) {
    const Session other = observe(boxSdf(box), test::floorPose(0.75, 0.85, 0.35), session++);
    const ConsistencyResult best = nearestToAcceptance(other);
    print("other box, nearest to acceptance", best);
    std::cout << "margin " << margin(best) << "\n";
    EXPECT_FALSE(best.accepted) << box.sizes().transpose();
    EXPECT_FALSE(best.reason.empty());
    EXPECT_LT(margin(best), -0.05) << box.sizes().transpose();
  }
}

TEST_F(Consistency, ACylinderIsRefusedAtEveryNearbyPose) {
  const Session other = observe(test::cylinderSdf(0.17, 0.4), test::floorPose(0.75, 0.85, 0.0), 4);
  const ConsistencyResult best = nearestToAcceptance(other);
  print("cylinder, nearest to acceptance", best);
  std::cout << "margin " << margin(best) << "\n";
  EXPECT_FALSE(best.accepted);
  EXPECT_FALSE(best.reason.empty());
  EXPECT_LT(margin(best), -0.05);
}

TEST_F(Consistency, AModelReachingIntoObservedFreeSpaceIsRefused) {
  // A taller box as the model; the session saw the space above its 40 cm box empty.
  const Session tall =
      observe(boxSdf(test::footBox(0.4, 0.3, 0.6)), test::floorPose(0.8, 0.8, 0.0), 5);
  const ObjectModel tall_model = foundModel(2, tall.observation, ObjectModelConfig{});
  const Session other = observe(boxSdf(kBox), test::floorPose(0.75, 0.85, 0.35), 2);
  ConsistencyConfig free_only;  // the SDF test switched off: the free-space test alone refuses
  free_only.min_agreement = 0.0f;
  free_only.min_overlap = 0.0f;
  const Eigen::Isometry3d T_M_O = trueT_M_O(tall, other);
  const ConsistencyResult r =
      checkConsistency(tall_model, other.observation, T_M_O, other.scene.map, free_only);
  print("taller model, free space only", r);
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.reason.find("free space"), std::string::npos) << r.reason;
  EXPECT_GT(r.free_space_violation, 0.15);
  const ConsistencyResult all =
      checkConsistency(tall_model, other.observation, T_M_O, other.scene.map);
  print("taller model", all);
  EXPECT_FALSE(all.accepted);
}

TEST(ObjectConsistencyConfig, BadFieldsAreNamed) {
  ConsistencyConfig c;
  c.min_overlap = 1.5f;
  try {
    c.validate();
    ADD_FAILURE() << "min_overlap 1.5 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("min_overlap"), std::string::npos);
  }
  c = ConsistencyConfig{};
  c.sdf_tolerance_voxels = 0.0f;
  EXPECT_THROW(c.validate(), InputError);
}

TEST(ObjectPrefilter, KeepsModelsWithinTheRatioNearestFirst) {
  ModelPrefilter filter;  // ratio 1.8, colour 60
  const Eigen::Vector3f grey(128, 128, 128), red(220, 30, 30);
  filter.upsert(1, {0.1f, 0.1f, 0.05f}, grey);
  filter.upsert(2, {0.2f, 0.15f, 0.15f}, grey);
  filter.upsert(3, {0.3f, 0.2f, 0.2f}, grey);
  filter.upsert(4, {0.5f, 0.3f, 0.3f}, grey);
  filter.upsert(5, {1.0f, 0.5f, 0.5f}, grey);
  filter.upsert(6, {0.31f, 0.2f, 0.2f}, red);
  EXPECT_EQ(filter.size(), 6u);
  // 0.3 m: the window [0.167, 0.54] m holds 2, 3, 4 (6 is red): nearest extent first.
  EXPECT_EQ(filter.candidates({0.3f, 0.2f, 0.2f}, grey), (std::vector<int>{3, 2, 4}));
  EXPECT_EQ(filter.candidates({0.3f, 0.2f, 0.2f}, red), (std::vector<int>{6}));
  // Colour off: all four in the window.
  ModelPrefilter colourless(PrefilterConfig{1.8f, 0.0f});
  colourless.upsert(3, {0.3f, 0.2f, 0.2f}, grey);
  colourless.upsert(6, {0.31f, 0.2f, 0.2f}, red);
  EXPECT_EQ(colourless.candidates({0.3f, 0.2f, 0.2f}, grey), (std::vector<int>{3, 6}));
  // Updating a model moves it: 5 shrinks into the window, 3 grows out of it.
  filter.upsert(5, {0.28f, 0.2f, 0.2f}, grey);
  filter.upsert(3, {2.0f, 1.0f, 1.0f}, grey);
  EXPECT_EQ(filter.size(), 6u);
  EXPECT_EQ(filter.candidates({0.3f, 0.2f, 0.2f}, grey), (std::vector<int>{5, 2, 4}));
  EXPECT_TRUE(filter.candidates({5.0f, 1.0f, 1.0f}, grey).empty());
  EXPECT_THROW(filter.upsert(7, {-0.1f, 0.1f, 0.1f}, grey), InputError);
  EXPECT_THROW(ModelPrefilter(PrefilterConfig{0.5f, 60.0f}), InputError);
}

TEST(ObjectPrefilter, ThousandRandomModelsGiveFewCandidates) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> log_size(std::log(0.05f), std::log(5.0f));
  std::uniform_real_distribution<float> channel(0.0f, 255.0f);
  ModelPrefilter filter;
  struct Model {
    Eigen::Vector3f extent, color;
  };
  std::vector<Model> models;
  for (int id = 0; id < 1000; ++id) {
    Eigen::Vector3f e(std::exp(log_size(rng)), std::exp(log_size(rng)), std::exp(log_size(rng)));
    std::sort(e.data(), e.data() + 3, std::greater<float>());
    models.push_back({e, Eigen::Vector3f(channel(rng), channel(rng), channel(rng))});
    filter.upsert(id, e, models.back().color);
  }
  std::size_t total = 0, most = 0;
  for (int q = 0; q < 50; ++q) {
    const Model& query = models[static_cast<std::size_t>(q * 17)];
    const std::vector<int> got = filter.candidates(query.extent, query.color);
    std::vector<int> expected;  // brute force over the whole database
    for (int id = 0; id < 1000; ++id) {
      const Model& m = models[static_cast<std::size_t>(id)];
      const float q_max = query.extent.maxCoeff(), m_max = m.extent.maxCoeff();
      if (m_max >= q_max / 1.8f && m_max <= q_max * 1.8f &&
          (m.color - query.color).norm() <= 60.0f) {
        expected.push_back(id);
      }
    }
    std::vector<int> sorted = got;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(sorted, expected);
    EXPECT_EQ(got.front(), q * 17);  // itself first
    total += got.size();
    most = std::max(most, got.size());
  }
  std::cout << "prefilter: 1000 models, " << total / 50.0 << " candidates on average, at most "
            << most << "\n";
  EXPECT_LT(most, 50u);  // under 5 % of the database
}

}  // namespace
}  // namespace strata::objects
