// MapHistory (ground truth): the surface a map last observed along a ray comes from the
// latest session whose fused keyframes saw it, not simply the previous session's world.
#include <gtest/gtest.h>

#include <memory>

#include "strata/core/error.h"
#include "strata/select/eval/map_history.h"

namespace strata::selection {
namespace {

/// A floor at height `z_m` everywhere (rays are cast straight down from z = 3 m).
class FloorScene : public sim::RayScene {
 public:
  explicit FloorScene(float z_m) : z_m_(z_m) {}
  void intersect(const std::vector<sim::Ray>& rays, std::vector<sim::RayHit>& hits) const override {
    hits.assign(rays.size(), sim::RayHit{});
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const float dz = rays[i].direction_W.z();
      if (!(dz < 0.0f)) continue;
      hits[i].t_m = (z_m_ - rays[i].origin_W.z()) / dz;
      hits[i].object_id = sim::kStaticObjectId;
    }
  }
  float signedDistance(const Eigen::Vector3f& p_W) const override { return p_W.z() - z_m_; }

 private:
  float z_m_;
};

sim::Ray downAt(float x_m, float y_m) {
  sim::Ray r;
  r.origin_W = Eigen::Vector3f(x_m, y_m, 3.0f);
  r.direction_W = Eigen::Vector3f(0.0f, 0.0f, -1.0f);
  return r;
}

TEST(MapHistory, LatestSessionThatSawThePlaceWins) {
  MapHistory history(0.1f);
  // Session 0 saw the floor (z = 0) at x = 0 and x = 1; session 1 (floor raised to 0.5 m: a
  // platform arrived) only saw x = 1.
  history.addSession(std::make_unique<FloorScene>(0.0f),
                     {Eigen::Vector3f(0.05f, 0.05f, 0.0f), Eigen::Vector3f(1.05f, 0.05f, 0.0f)});
  history.addSession(std::make_unique<FloorScene>(0.5f), {Eigen::Vector3f(1.05f, 0.05f, 0.5f)});
  ASSERT_EQ(history.sessionCount(), 2);
  const std::vector<float> d = history.lastObservedDistance(
      {downAt(0.05f, 0.05f), downAt(1.05f, 0.05f), downAt(5.05f, 0.05f)});
  ASSERT_EQ(d.size(), 3u);
  EXPECT_FLOAT_EQ(d[0], 3.0f);  // session 1 never looked at x = 0: the map holds session 0's floor
  EXPECT_FLOAT_EQ(d[1], 2.5f);  // session 1 saw the platform
  EXPECT_LT(d[2], 0.0f);        // nobody saw x = 5
}

TEST(MapHistory, EmptyHistoryAndBadInput) {
  MapHistory history;
  EXPECT_LT(history.lastObservedDistance({downAt(0.0f, 0.0f)}).at(0), 0.0f);
  EXPECT_THROW(history.addSession(nullptr, {}), InputError);
  EXPECT_THROW({ MapHistory bad(0.0f); }, InputError);
}

}  // namespace
}  // namespace strata::selection
