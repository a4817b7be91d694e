// Encodes a camera pose as Strata's LCM pose_t (what strata-mapper reads on STRATA_POSE),
// publishes it over LCM's in-process provider (memq://: no network), receives it, decodes it and
// prints what arrived.   lcm_pose
#include <Eigen/Geometry>
#include <cstdio>
#include <exception>
#include <lcm/lcm-cpp.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "strata/lcm/channels.h"
#include "strata/lcm/convert_pose.h"
#include "strata/pose_t.hpp"

namespace {

// Keeps the decoded message; checks that may throw run outside LCM's (C) dispatch.
void onPose(const lcm::ReceiveBuffer*, const std::string& channel, const strata::pose_t* msg,
            std::optional<strata::pose_t>* received) {
  std::printf("received on %s: utime %lld, %s -> %s\n", channel.c_str(),
              static_cast<long long>(msg->utime), msg->child_frame.c_str(),
              msg->parent_frame.c_str());
  *received = *msg;
}

}  // namespace

int main() {
  try {
    lcm::LCM lcm("memq://");
    if (!lcm.good()) throw std::runtime_error("LCM could not start the memq:// provider");
    std::optional<strata::pose_t> received;
    lcm.subscribeFunction(strata::lcm_io::kPoseChannel, &onPose, &received);

    const Eigen::Isometry3d T_W_C =
        Eigen::Translation3d(1.0, -2.0, 0.5) * Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ());
    const strata::pose_t message = strata::lcm_io::encodePose(T_W_C, /*utime=*/1'000'000);
    if (lcm.publish(strata::lcm_io::kPoseChannel, &message) != 0)
      throw std::runtime_error("publish failed");
    if (lcm.handleTimeout(1000) <= 0 || !received) throw std::runtime_error("nothing received");

    // decodePose() checks the message (finite values, a unit quaternion) before it is used.
    const Eigen::Isometry3d T = strata::lcm_io::decodePose(*received);
    const Eigen::Vector3d t = T.translation();
    const Eigen::AngleAxisd r(T.rotation());
    std::printf(
        "T_W_C: translation (%.3f, %.3f, %.3f) m, rotation %.3f rad about (%.2f, %.2f, %.2f)\n",
        t.x(), t.y(), t.z(), r.angle(), r.axis().x(), r.axis().y(), r.axis().z());
    const bool same = T.isApprox(T_W_C, 1e-12);
    std::printf("round trip: %s\n", same ? "the pose sent" : "DIFFERS from the pose sent");
    return same ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lcm_pose: %s\n", e.what());
    return 1;
  }
}
