#include "localizer_node/localizer_core.h"

#include <chrono>
#include <cstdio>
#include <string>

#include "strata/core/error.h"
#include "strata/store/session_store.h"

namespace strata::apps {
namespace {

constexpr double kSecondsPerUtime = 1e-6;

const LocalizerOptions& validated(const LocalizerOptions& options) {
  options.localizer.validate();
  options.fusion.validate();
  return options;
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

/// The adjoint of T for perturbations ordered (translation, rotation).
Eigen::Matrix<double, 6, 6> adjoint(const Eigen::Isometry3d& T) {
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
  A.topLeftCorner<3, 3>() = T.linear();
  A.topRightCorner<3, 3>() = skew(T.translation()) * T.linear();
  A.bottomRightCorner<3, 3>() = T.linear();
  return A;
}

}  // namespace

localize::Localization carryLocalization(const localize::Localization& l,
                                         const Eigen::Isometry3d& T_O_C_frame,
                                         const Eigen::Isometry3d& T_O_C_now) {
  localize::Localization carried = l;
  const Eigen::Isometry3d D = T_O_C_frame.inverse() * T_O_C_now;
  carried.T_W_C = l.T_W_C * D;
  // T * Exp(d) * D = T * D * Exp(Ad(D^-1) d).
  const Eigen::Matrix<double, 6, 6> A = adjoint(D.inverse());
  carried.covariance = A * l.covariance * A.transpose();
  return carried;
}

localize::PriorMap loadPriorMap(const LocalizerOptions& options) {
  store::StoreOptions store_options;
  store_options.read_only = true;
  const auto start = std::chrono::steady_clock::now();
  try {
    store::Store store(options.db_path, store_options);
    localize::PriorMap map = localize::PriorMap::fromStore(store, options.map);
    if (!options.quiet) {
      std::fprintf(stderr,
                   "strata-localizer: prior map %s: %zu keyframes of %zu session(s) (%zu left "
                   "out: not aligned), loaded in %.1f s\n",
                   options.db_path.c_str(), map.keyframes().size(), map.sessions().size(),
                   map.skipped_sessions().size(),
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    return map;
  } catch (const InputError& e) {
    throw InputError("cannot use the prior map '" + options.db_path + "': " + e.what());
  }
}

LocalizerCore::LocalizerCore(const localize::PriorMap& map, const LocalizerOptions& options)
    : map_(map), localizer_(map, validated(options).localizer), fusion_(options.fusion) {}

localize::FusedPose LocalizerCore::odometry(std::int64_t utime, const Eigen::Isometry3d& T_O_C,
                                            double* gap_s) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (have_odometry_ && utime <= last_utime_) {
    throw InputError(std::string(utime == last_utime_ ? "odometry time repeats"
                                                      : "odometry time goes backwards") +
                     ": pose at utime " + std::to_string(utime) + " after one at " +
                     std::to_string(last_utime_) + " (refused)");
  }
  const localize::FusedPose fused =
      fusion_.predict(static_cast<double>(utime) * kSecondsPerUtime, T_O_C);  // throws: unchanged
  if (gap_s != nullptr) {
    *gap_s = have_odometry_ ? static_cast<double>(utime - last_utime_) * kSecondsPerUtime : 0.0;
  }
  have_odometry_ = true;
  last_utime_ = utime;
  last_T_O_C_ = T_O_C;
  return fused;
}

std::optional<localize::PosePrior> LocalizerCore::priorFor(const Eigen::Isometry3d& T_O_C) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!fusion_.initialised()) return std::nullopt;
  return localize::PosePrior{fusion_.T_W_O() * T_O_C};
}

localize::Localization LocalizerCore::localize(
    const lcm_io::ReadyFrame& frame, const std::optional<localize::PosePrior>& prior) const {
  return localizer_.localize(frame.frame.color, frame.frame.depth, frame.intrinsics, prior);
}

localize::FusedPose LocalizerCore::correct(const localize::Localization& l,
                                           const Eigen::Isometry3d& T_O_C_frame) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!l.localized) return fusion_.correct(l);  // nothing to carry
  return fusion_.correct(carryLocalization(l, T_O_C_frame, last_T_O_C_));
}

bool LocalizerCore::initialised() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return fusion_.initialised();
}

std::size_t LocalizerCore::accepted() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return fusion_.accepted();
}

std::size_t LocalizerCore::rejected() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return fusion_.rejected();
}

}  // namespace strata::apps
