#pragma once
// The redkitchen excerpt split in two sessions, as the alignment and localisation tests use it:
// frames 0-74 with the reference poses as their odometry (no offset, no drift: the session's
// frame is the dataset's) and frames 75-149 in a random frame of their own (seed 3) with
// drifting odometry. Images are listed, not copied.
#include <Eigen/Geometry>
#include <filesystem>
#include <string>

#include "strata/sim/session/drifted_session.h"
#include "store_test_helpers.h"

namespace strata::test {

struct SplitKitchen {
  std::filesystem::path root, first, second;
  Eigen::Isometry3d T_W_S_second = Eigen::Isometry3d::Identity();  // the second's true frame
};

/// Writes both halves into a fresh folder named after `name`: root/<first_name>, root/<second_name>;
/// the second drifts by `translation_sigma` per axis per sqrt(metre) (and the default yaw drift).
inline SplitKitchen splitKitchen(const std::string& kitchen, const std::string& name,
                                 const std::string& first_name, const std::string& second_name,
                                 double translation_sigma) {
  SplitKitchen out;
  out.root = freshStoreDir(name);
  out.first = out.root / first_name;
  out.second = out.root / second_name;
  sim::DriftedSessionConfig a;
  a.first_frame = 0;
  a.last_frame = 74;
  a.offset = false;
  a.drift.translation_sigma_m_per_sqrt_m = 0.0;
  a.drift.yaw_sigma_rad_per_sqrt_m = 0.0;
  sim::writeDriftedSession(kitchen, out.first.string(), a);
  sim::DriftedSessionConfig b;
  b.first_frame = 75;
  b.last_frame = 149;
  b.seed = 3;
  b.drift.translation_sigma_m_per_sqrt_m = translation_sigma;
  out.T_W_S_second = sim::writeDriftedSession(kitchen, out.second.string(), b).T_W_S;
  return out;
}

}  // namespace strata::test
