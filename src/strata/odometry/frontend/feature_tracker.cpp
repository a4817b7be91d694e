#include "strata/core/clock.h"
#include "strata/odometry/frontend/feature_tracker.h"

#include <algorithm>
#include <sstream>

#include "strata/core/error.h"

namespace strata::odometry {
namespace {

const char* depthName(int depth) {
  switch (depth) {
    case CV_8U:
      return "8-bit unsigned";
    case CV_8S:
      return "8-bit signed";
    case CV_16U:
      return "16-bit unsigned";
    case CV_16S:
      return "16-bit signed";
    case CV_32S:
      return "32-bit integer";
    case CV_32F:
      return "32-bit float";
    case CV_64F:
      return "64-bit float";
    default:
      return "unknown depth";
  }
}

double medianOf(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

Eigen::Vector2d toEigen(const cv::Point2f& p) { return {p.x, p.y}; }

StereoCamera monoRig(const Camera& camera) {
  StereoCamera rig;
  rig.left = camera;
  rig.right = camera;
  return rig;
}

}  // namespace

void FrontendConfig::validate() const {
  detector.validate();
  klt.validate();
  geometry.validate();
  stereo.validate();
  keyframe.validate();
  if (min_tracked < 0) throw InputError("FrontendConfig: min_tracked must be >= 0");
  if (!(border_px >= 0.0)) throw InputError("FrontendConfig: border_px must be >= 0");
  if (appearance_patch_px < 3 || appearance_patch_px % 2 == 0) {
    throw InputError("FrontendConfig: appearance_patch_px must be odd and >= 3");
  }
  if (!(min_appearance_ncc >= 0.0 && min_appearance_ncc < 1.0)) {
    throw InputError("FrontendConfig: min_appearance_ncc must be in [0, 1)");
  }
}

FeatureTracker::FeatureTracker(const Camera& camera, FrontendConfig config)
    : camera_(monoRig(camera)), stereo_(false), config_(config), keyframes_(config.keyframe) {
  camera_.left.validate();
  config_.validate();
}

FeatureTracker::FeatureTracker(const StereoCamera& camera, FrontendConfig config)
    : camera_(camera), stereo_(true), config_(config), keyframes_(config.keyframe) {
  camera_.validate();
  config_.validate();
}

void FeatureTracker::checkImage(const cv::Mat& image, const Camera& camera) const {
  const std::string eye = "FeatureTracker: " + camera.name + " image";
  if (image.empty()) throw InputError(eye + " is empty");
  if (image.channels() != 1) {
    throw InputError(eye + " has " + std::to_string(image.channels()) +
                     " channels; the front end needs single-channel 8-bit grey");
  }
  if (image.depth() != CV_8U) {
    throw InputError(eye + " is " + depthName(image.depth()) +
                     "; the front end needs single-channel 8-bit grey");
  }
  if (image.cols != camera.width_px || image.rows != camera.height_px) {
    std::ostringstream msg;
    msg << eye << " is " << image.cols << "x" << image.rows << " px but the calibration is "
        << camera.width_px << "x" << camera.height_px << " px";
    throw InputError(msg.str());
  }
}

void FeatureTracker::trackPrevious(const std::vector<cv::Mat>& pyramid,
                                   const std::optional<Eigen::Matrix3d>& R_Ck_Ckm1,
                                   FrontendStats* stats) {
  const Camera& cam = camera_.left;
  std::vector<cv::Point2f> from, to;
  for (const Track& t : tracks_) {
    from.push_back(t.uv_px);
    Eigen::Vector2d guess = toEigen(t.uv_px);
    if (R_Ck_Ckm1) {
      // Infinite-depth prediction: the rotation alone moves far points exactly.
      const Eigen::Vector3d bearing = *R_Ck_Ckm1 * t.xy_norm.homogeneous();
      if (bearing.z() > 1e-3) guess = cam.projectPoint(bearing);
    }
    to.emplace_back(static_cast<float>(guess.x()), static_cast<float>(guess.y()));
  }
  const std::vector<KltStatus> status =
      trackForwardBackward(previous_pyramid_, pyramid, from, &to,
                           cv::Size(cam.width_px, cam.height_px), config_.border_px, config_.klt);
  std::vector<Track> moved;
  std::vector<Eigen::Vector2d> xy_prev, xy_cur;
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    if (status[i] == KltStatus::kFailed) ++stats->rejected_klt;
    if (status[i] == KltStatus::kFwdBwd) ++stats->rejected_fwd_bwd;
    if (status[i] != KltStatus::kOk) continue;
    if (config_.min_appearance_ncc > 0.0 &&
        patchNcc(tracks_[i].patch,
                 normalizedPatch(pyramid[0], to[i], config_.appearance_patch_px)) <
            config_.min_appearance_ncc) {
      ++stats->rejected_appearance;
      continue;
    }
    Track t = tracks_[i];
    xy_prev.push_back(t.xy_norm);
    if (t.uv_right_px) *t.uv_right_px += toEigen(to[i]) - toEigen(t.uv_px);
    t.uv_px = to[i];
    t.xy_norm = cam.undistort(toEigen(to[i]));
    xy_cur.push_back(t.xy_norm);
    moved.push_back(t);
  }
  const GeometricCheckResult check =
      rejectOutliers(xy_prev, xy_cur, R_Ck_Ckm1, cam.focalMean(), config_.geometry);
  stats->geometric_model = check.model;
  stats->rejected_geometry = check.rejected;
  std::vector<double> flow;
  tracks_.clear();
  for (std::size_t i = 0; i < moved.size(); ++i) {
    if (!check.inlier[i]) continue;
    ++moved[i].length;
    flow.push_back(cam.focalMean() * (xy_cur[i] - xy_prev[i]).norm());
    tracks_.push_back(moved[i]);
  }
  stats->tracked = static_cast<int>(tracks_.size());
  stats->median_flow_px = medianOf(flow);
}

void FeatureTracker::addNewCorners(const cv::Mat& left, FrontendStats* stats) {
  const int wanted = config_.detector.target_features - static_cast<int>(tracks_.size());
  if (wanted <= 0) return;
  std::vector<cv::Point2f> existing;
  for (const Track& t : tracks_) existing.push_back(t.uv_px);
  for (const cv::Point2f& p : detectCorners(left, existing, wanted, config_.detector)) {
    tracks_.push_back(Track{next_id_++, p, camera_.left.undistort(toEigen(p)), 1, std::nullopt,
                            normalizedPatch(left, p, config_.appearance_patch_px)});
    ++stats->detected;
  }
}

void FeatureTracker::matchRight(const std::vector<cv::Mat>& pyramid_left, const cv::Mat& right,
                                std::vector<std::optional<StereoMatch>>* matches,
                                FrontendStats* stats) {
  cv::Mat adjusted = right;
  if (config_.stereo.match_brightness) {
    cv::Scalar ml, sl, mr, sr;
    cv::meanStdDev(pyramid_left[0], ml, sl);
    cv::meanStdDev(right, mr, sr);
    const double gain = sl[0] / std::max(sr[0], 1.0);
    right.convertTo(adjusted, CV_8U, gain, ml[0] - gain * mr[0]);
  }
  const std::vector<cv::Mat> pyramid_right = buildPyramid(adjusted, config_.klt);
  std::vector<Eigen::Vector2d> uv, xy;
  std::vector<std::optional<Eigen::Vector2d>> guess;
  std::vector<bool> retry_near;
  for (const Track& t : tracks_) {
    uv.push_back(toEigen(t.uv_px));
    xy.push_back(t.xy_norm);
    guess.push_back(t.uv_right_px);
    retry_near.push_back(t.length == 1);
  }
  *matches = matchStereo(pyramid_left, pyramid_right, camera_, uv, xy, guess, retry_near,
                         config_.klt, config_.border_px, config_.stereo);
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    const std::optional<StereoMatch>& m = (*matches)[i];
    tracks_[i].uv_right_px = m ? std::optional<Eigen::Vector2d>(m->uv_right_px) : std::nullopt;
    if (m) {
      ++stats->stereo_matched;
    } else {
      ++stats->stereo_rejected;
    }
  }
}

FrameFeatures FeatureTracker::process(std::int64_t timestamp_ns, const cv::Mat& left,
                                      const cv::Mat& right,
                                      const std::optional<Eigen::Matrix3d>& R_Ck_Ckm1) {
  const auto start = std::chrono::steady_clock::now();
  checkImage(left, camera_.left);
  if (stereo_) checkImage(right, camera_.right);
  if (previous_timestamp_ns_ && timestamp_ns <= *previous_timestamp_ns_) {
    throw InputError("FeatureTracker: timestamp " + std::to_string(timestamp_ns) +
                     " ns does not follow the previous frame's " +
                     std::to_string(*previous_timestamp_ns_) + " ns");
  }
  FrameFeatures out;
  out.timestamp_ns = timestamp_ns;
  FrontendStats& stats = out.stats;
  auto mark = start;
  const auto lap = [&mark] {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - mark).count();
    mark = now;
    return ms;
  };
  std::vector<cv::Mat> pyramid = buildPyramid(left, config_.klt);
  stats.pyramid_ms = lap();
  const bool has_previous = previous_timestamp_ns_.has_value();
  if (has_previous) trackPrevious(pyramid, R_Ck_Ckm1, &stats);
  stats.lost = has_previous && stats.tracked < config_.min_tracked;
  stats.track_ms = lap();
  addNewCorners(left, &stats);
  stats.detect_ms = lap();
  std::vector<std::optional<StereoMatch>> matches(tracks_.size());
  if (stereo_) matchRight(pyramid, right, &matches, &stats);
  stats.stereo_ms = lap();

  out.features.reserve(tracks_.size());
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    const Track& t = tracks_[i];
    FeatureObservation f;
    f.track_id = t.id;
    f.uv_left_px = toEigen(t.uv_px);
    f.xy_left_norm = t.xy_norm;
    f.track_length = t.length;
    if (matches[i]) {
      f.uv_right_px = matches[i]->uv_right_px;
      f.xy_right_norm = matches[i]->xy_right_norm;
    }
    out.features.push_back(f);
  }
  out.is_keyframe = keyframes_.decide(timestamp_ns, out.features, R_Ck_Ckm1,
                                      camera_.left.focalMean(), stats.lost, &stats.parallax_px);
  previous_pyramid_ = std::move(pyramid);
  previous_timestamp_ns_ = timestamp_ns;
  stats.process_time_ms =
      msSince(start);
  return out;
}

}  // namespace strata::odometry
