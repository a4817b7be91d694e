#include "object_test_scene.h"

#include <algorithm>
#include <cmath>

namespace strata::test {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

Eigen::Isometry3d Thing::T_W_P() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_deg * kPi / 180.0, Eigen::Vector3d::UnitZ()).matrix();
  T.translation() = Eigen::Vector3d(at_m.x(), at_m.y(), 0.0);
  return T;
}

double Thing::sdfW(const Eigen::Vector3d& p_W) const { return sdf_P(T_W_P().inverse() * p_W); }

double lShapeSdf(const Eigen::Vector3d& p) {
  const Eigen::AlignedBox3d wall(Eigen::Vector3d(-0.25, -0.15, -0.1),
                                 Eigen::Vector3d(0.25, 0.0, 0.45));
  const Eigen::AlignedBox3d wing(Eigen::Vector3d(-0.25, 0.0, -0.1),
                                 Eigen::Vector3d(-0.05, 0.2, 0.3));
  return std::min(boxSdf(p, wall), boxSdf(p, wing));
}

double boxShapeSdf(const Eigen::Vector3d& p) {
  return boxSdf(p, Eigen::AlignedBox3d(Eigen::Vector3d(-0.22, -0.15, -0.1),
                                       Eigen::Vector3d(0.22, 0.15, 0.4)));
}

Session makeSession(const std::vector<Thing>& things, int session) {
  const auto sdf = [&](const Eigen::Vector3d& p) {
    double d = p.z();
    for (const Thing& t : things) d = std::min(d, t.sdfW(p));
    return d;
  };
  const auto observed = [&](const Eigen::Vector3d& p) {
    if (p.x() < 0.05 || p.y() < 0.05 || p.x() > 1.95 || p.y() > 1.95) return false;
    for (const Thing& t : things) {
      if (t.sdfW(p) < 0.15 && !t.observed_P(t.T_W_P().inverse() * p)) return false;
    }
    return true;
  };
  Session s;
  s.map = makeSdfMap(sdf, {0, 0, -0.1}, {2, 2, 0.7}, kVoxel, observed);
  const change::LabelMap labels = makeLabels(s.map, [&](const Eigen::Vector3d& p) {
    return std::any_of(things.begin(), things.end(),
                       [&](const Thing& t) { return t.sdfW(p) < 3 * kVoxel; });
  });
  s.segments =
      change::extractObjects(s.map, labels, change::ObjectConfig{}, session, nullptr, &s.surface);
  return s;
}

const Thing kL1{lShapeSdf, {0.7, 0.8}, 0.0, [](const Eigen::Vector3d& p) { return p.y() < 0.1; }};
const Thing kL2{lShapeSdf, {0.6, 0.6}, 70.0, [](const Eigen::Vector3d& p) { return p.y() < 0.0; }};
const Thing kL3{
    lShapeSdf, {1.2, 1.1}, 200.0, [](const Eigen::Vector3d& p) { return p.y() > -0.1; }};
const Thing kBox{boxShapeSdf, {1.4, 1.4}, 30.0};

const Fixture& threeSessions() {
  static const Fixture fixture = [] {
    Fixture f;
    const std::vector<std::vector<Thing>> sessions = {{kL1}, {kL2, kBox}, {kL3}};
    for (std::size_t i = 0; i < sessions.size(); ++i) {
      const int id = static_cast<int>(i) + 1;
      const Session s = makeSession(sessions[i], id);
      f.outcomes.push_back(f.database.addSession(id, s.map, s.surface, s.segments));
    }
    return f;
  }();
  return fixture;
}

}  // namespace strata::test
