#include "strata/sim/world/internal/truth_builder.h"

#include <cmath>

#include "strata/sim/rng.h"
#include "strata/sim/world/shape_mesh.h"
#include "strata/core/math_constants.h"

namespace strata::sim {
namespace {

constexpr std::uint64_t kLightStream = 0x4C49474854ull;  // "LIGHT": apart from the layout streams

Change compare(const Placement& reference, const Placement& now) {
  if (reference.present && now.present) {
    const bool same = reference.at_m == now.at_m && reference.yaw_deg == now.yaw_deg;
    return same ? Change::kNone : Change::kMoved;
  }
  if (reference.present) return Change::kRemoved;
  return now.present ? Change::kAdded : Change::kNone;
}

/// The file's light, tilted by up to vary_direction_deg about a random axis and scaled by
/// 1 + uniform(-vary_intensity, vary_intensity). Session 0 keeps the file's light.
Light sessionLight(const WorldSpec& spec, int session) {
  const LightingSpec& base = spec.lighting;
  Light light{base.direction_W.normalized(), base.intensity, base.ambient};
  if (session == 0) return light;
  Rng rng(hashCombine(spec.seed ^ kLightStream, static_cast<std::uint64_t>(session)));
  const double tilt = rng.uniform(0.0, base.vary_direction_deg) * kPi / 180.0;
  const double azimuth = rng.uniform(0.0, 2.0 * kPi);
  const Eigen::Vector3d d = light.direction_W;
  const Eigen::Vector3d u = d.unitOrthogonal(), v = d.cross(u);
  const Eigen::Vector3d axis = std::cos(azimuth) * u + std::sin(azimuth) * v;
  light.direction_W = Eigen::AngleAxisd(tilt, axis) * d;
  light.intensity *= 1.0 + rng.uniform(-base.vary_intensity, base.vary_intensity);
  return light;
}

/// Where an object stands: its placement now, else its last placement, else its first.
Placement lastKnown(const std::vector<Layout>& layouts, int session, std::size_t i) {
  for (int s = session; s >= 0; --s) {
    if (layouts[s][i].present) return layouts[s][i];
  }
  for (const Layout& layout : layouts) {
    if (layout[i].present) return layout[i];
  }
  return Placement{};
}

}  // namespace

std::vector<SessionTruth> makeSessionTruths(const WorldSpec& spec,
                                            const std::vector<ObjectSpec>& objects,
                                            const std::vector<Layout>& layouts) {
  std::vector<SessionTruth> sessions;
  for (int s = 0; s < static_cast<int>(layouts.size()); ++s) {
    SessionTruth truth;
    truth.index = s;
    truth.light = sessionLight(spec, s);
    for (std::size_t i = 0; i < objects.size(); ++i) {
      const Placement& now = layouts[s][i];
      const Placement pose = lastKnown(layouts, s, i);
      ObjectState state;
      state.id = static_cast<int>(i) + 1;
      state.name = objects[i].name;
      state.shape = objects[i].shape.kind;
      state.present = now.present;
      state.at_m = pose.at_m;
      state.yaw_deg = pose.yaw_deg;
      state.T_W_O = floorPose(pose.at_m, pose.yaw_deg);
      state.since_previous = s == 0 ? Change::kNone : compare(layouts[s - 1][i], now);
      state.since_first = compare(layouts[0][i], now);
      truth.objects.push_back(state);
    }
    sessions.push_back(std::move(truth));
  }
  return sessions;
}

}  // namespace strata::sim
