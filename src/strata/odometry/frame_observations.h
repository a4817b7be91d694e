#pragma once
// One camera frame for the back end: the front end's observations (odometry/frontend/
// feature_observation.h) on the IMU's clock. The back end reads the undistorted normalized
// coordinates (xy_left_norm, xy_right_norm) and turns them into pixels of the rig's pinhole
// model (camera_rig.h), so its pixel sigma and Huber threshold are in pixels of that model.
#include <vector>

#include "strata/odometry/frontend/feature_observation.h"

namespace strata::odometry {

struct FrameObservations {
  double t_s = 0.0;  // same clock as ImuMeasurement::t_s (e.g. FrameFeatures::timestamp_ns
                     // minus a session epoch, in seconds)
  std::vector<FeatureObservation> features;
};

}  // namespace strata::odometry
