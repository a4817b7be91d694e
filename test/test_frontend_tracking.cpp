// Visual front end on images: the simulator's stereo grey camera along a known trajectory (tracks
// checked against the true 3D points, stereo against the true depth, a moving patch rejected),
// bad input named, and the real EuRoC V1_01 excerpt (a still vehicle) when the data is present.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "strata/core/error.h"
#include "strata/odometry/frontend/feature_tracker.h"
#include "strata/sim/default_scene.h"
#include "strata/sim/sensors/analytic_ray_scene.h"
#include "strata/sim/sensors/grey_camera.h"
#include "test_utils.h"

namespace strata::odometry {
namespace {

// ---------------------------------------------------------------------------------------------
// A textured room seen by a 752x480 stereo pair (EuRoC's size, baseline 0.11 m), sliding
// sideways while it turns: 3 cm and 0.4 degrees per frame.

constexpr int kWidth = 752, kHeight = 480, kFrames = 12;
constexpr double kFocal = 460.0, kBaseline = 0.11;

// Left-eye pose of frame k: camera z along world +y, x along +x, y down (-z).
Eigen::Isometry3d leftPose(int k) {
  Eigen::Matrix3d R_W_C0;
  R_W_C0.col(0) = Eigen::Vector3d::UnitX();
  R_W_C0.col(1) = -Eigen::Vector3d::UnitZ();
  R_W_C0.col(2) = Eigen::Vector3d::UnitY();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(-0.2 + 0.03 * k, -1.5, 1.3 + 0.005 * k);
  T.linear() = Eigen::AngleAxisd(0.007 * k, Eigen::Vector3d::UnitZ()) * R_W_C0;
  return T;
}

CameraIntrinsics intrinsics() {
  CameraIntrinsics k;
  k.width_px = kWidth;
  k.height_px = kHeight;
  k.fx_px = k.fy_px = static_cast<float>(kFocal);
  k.cx_px = 0.5f * (kWidth - 1);
  k.cy_px = 0.5f * (kHeight - 1);
  return k;
}

StereoCamera simRig() {
  StereoCamera rig;
  rig.left = Camera::fromIntrinsics(intrinsics(), "sim left");
  rig.right = Camera::fromIntrinsics(intrinsics(), "sim right");
  rig.right.T_B_C = Eigen::Isometry3d(Eigen::Translation3d(kBaseline, 0, 0));
  return rig;
}

cv::Mat toMat(const sim::GreyImage& image) {
  return cv::Mat(image.height_px, image.width_px, CV_8UC1,
                 const_cast<std::uint8_t*>(image.pixels.data()))
      .clone();
}

struct SimSequence {
  sim::AnalyticRayScene scene = sim::makeStereoTestRoom(2);
  std::vector<cv::Mat> left, right;
};

// Rendered once for every test of this file (~1 s).
const SimSequence& simSequence() {
  static const SimSequence* sequence = [] {
    auto* s = new SimSequence;
    sim::GreyCameraConfig config;
    config.intrinsics = intrinsics();
    config.baseline_m = kBaseline;
    config.threads = 2;
    const sim::GreyCamera camera(config);
    for (int k = 0; k < kFrames; ++k) {
      const sim::GreyFrame f = camera.render(s->scene, leftPose(k), sim::Lighting{}, 100 + k);
      s->left.push_back(toMat(f.eyes[0]));
      s->right.push_back(toMat(f.eyes[1]));
    }
    return s;
  }();
  return *sequence;
}

// True world point behind a left-eye pixel of frame k (nullopt on a miss).
std::optional<Eigen::Vector3d> truePoint(const sim::AnalyticRayScene& scene, int k,
                                         const Eigen::Vector2d& uv) {
  const Eigen::Isometry3d T = leftPose(k);
  const Eigen::Vector3d dir_C((uv.x() - 0.5 * (kWidth - 1)) / kFocal,
                              (uv.y() - 0.5 * (kHeight - 1)) / kFocal, 1.0);
  const sim::RayHit hit = scene.castRay(T.translation(), T.linear() * dir_C.normalized(), 100.0);
  if (!hit.hit()) return std::nullopt;
  return T.translation() + T.linear() * dir_C.normalized() * static_cast<double>(hit.t_m);
}

Eigen::Vector2d projectLeft(int k, const Eigen::Vector3d& p_W) {
  const Eigen::Vector3d p_C = leftPose(k).inverse() * p_W;
  return {kFocal * p_C.x() / p_C.z() + 0.5 * (kWidth - 1),
          kFocal * p_C.y() / p_C.z() + 0.5 * (kHeight - 1)};
}

double median(std::vector<double> v) {
  if (v.empty()) return 1e9;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

std::int64_t stamp(int k) { return 1'000'000'000 + 50'000'000LL * k; }

// Linear N-view triangulation (DLT) of one track from its left-eye pixels and the true poses.
Eigen::Vector3d triangulate(const std::vector<std::pair<int, Eigen::Vector2d>>& track) {
  Eigen::MatrixXd A(2 * track.size(), 4);
  for (std::size_t i = 0; i < track.size(); ++i) {
    const Eigen::Matrix<double, 3, 4> P = leftPose(track[i].first).inverse().matrix().topRows<3>();
    const Eigen::Vector2d xy((track[i].second.x() - 0.5 * (kWidth - 1)) / kFocal,
                             (track[i].second.y() - 0.5 * (kHeight - 1)) / kFocal);
    A.row(2 * i) = xy.x() * P.row(2) - P.row(0);
    A.row(2 * i + 1) = xy.y() * P.row(2) - P.row(1);
  }
  const Eigen::Vector4d X =
      Eigen::JacobiSVD<Eigen::MatrixXd>(A, Eigen::ComputeFullV).matrixV().col(3);
  return X.hnormalized();
}

// Scores the tracks against the true poses (each track triangulated from its observations,
// every observation's reprojection error; the same 3D point along the track gives ~0) and every
// stereo match against the true depth of the ray cast through its left pixel.
struct TruthScore {
  std::vector<double> track_error_px;   // observations of tracks seen in >= 3 frames
  std::vector<double> stereo_error_px;  // right-eye position vs the true disparity
  int features = 0, rejected_appearance = 0, stereo_matched = 0, lost_frames = 0, keyframes = 0;
  int rejected_geometry = 0, min_tracked = 1 << 30;

  double outlierShare(const std::vector<double>& errors, double bound_px) const {
    const auto n =
        std::count_if(errors.begin(), errors.end(), [&](double e) { return e > bound_px; });
    return errors.empty() ? 1.0 : static_cast<double>(n) / errors.size();
  }
};

// The figure of docs/odometry.md: the last left image with each live track's trail (green:
// stereo-matched now, red: left only), written where STRATA_TEST_OUTPUT points.
void writeTrackFigure(const std::string& name, const cv::Mat& image,
                      const std::vector<FeatureObservation>& features,
                      const std::map<std::uint64_t, std::vector<Eigen::Vector2d>>& trails) {
  const char* dir = std::getenv("STRATA_TEST_OUTPUT");
  if (dir == nullptr) return;
  cv::Mat figure;
  cv::cvtColor(image, figure, cv::COLOR_GRAY2BGR);
  const auto point = [](const Eigen::Vector2d& p) {
    return cv::Point(cvRound(p.x()), cvRound(p.y()));
  };
  for (const FeatureObservation& f : features) {
    const cv::Scalar colour = f.uv_right_px ? cv::Scalar(40, 220, 40) : cv::Scalar(40, 40, 230);
    const std::vector<Eigen::Vector2d>& trail = trails.at(f.track_id);
    for (std::size_t i = 1; i < trail.size(); ++i) {
      cv::line(figure, point(trail[i - 1]), point(trail[i]), colour, 1, cv::LINE_AA);
    }
    cv::circle(figure, point(f.uv_left_px), 3, colour, 1, cv::LINE_AA);
  }
  cv::imwrite(std::string(dir) + "/" + name, figure);
}

TruthScore runAndScore(const std::vector<cv::Mat>& left, const std::vector<cv::Mat>& right,
                       bool predict_rotation, const std::string& figure = "") {
  const SimSequence& seq = simSequence();
  FeatureTracker tracker(simRig(), FrontendConfig{});
  std::map<std::uint64_t, std::vector<std::pair<int, Eigen::Vector2d>>> tracks;
  TruthScore score;
  std::vector<FeatureObservation> last_features;
  for (int k = 0; k < kFrames; ++k) {
    std::optional<Eigen::Matrix3d> R_Ck_Ckm1;
    if (predict_rotation && k > 0) {
      R_Ck_Ckm1 = leftPose(k).linear().transpose() * leftPose(k - 1).linear();
    }
    const FrameFeatures frame = tracker.process(stamp(k), left[k], right[k], R_Ck_Ckm1);
    last_features = frame.features;
    score.lost_frames += frame.stats.lost;
    score.keyframes += frame.is_keyframe;
    score.rejected_geometry += frame.stats.rejected_geometry;
    score.rejected_appearance += frame.stats.rejected_appearance;
    if (k > 0) score.min_tracked = std::min(score.min_tracked, frame.stats.tracked);
    for (const FeatureObservation& f : frame.features) {
      ++score.features;
      tracks[f.track_id].emplace_back(k, f.uv_left_px);
      EXPECT_EQ(static_cast<int>(tracks[f.track_id].size()), f.track_length);
      if (!f.uv_right_px) continue;
      ++score.stereo_matched;
      const std::optional<Eigen::Vector3d> here_W = truePoint(seq.scene, k, f.uv_left_px);
      if (!here_W) continue;
      const double z = (leftPose(k).inverse() * *here_W).z();
      const Eigen::Vector2d expected = f.uv_left_px - Eigen::Vector2d(kFocal * kBaseline / z, 0);
      score.stereo_error_px.push_back((*f.uv_right_px - expected).norm());
    }
  }
  if (!figure.empty()) {
    std::map<std::uint64_t, std::vector<Eigen::Vector2d>> trails;
    for (const auto& [id, track] : tracks) {
      for (const auto& obs : track) trails[id].push_back(obs.second);
    }
    writeTrackFigure(figure, left.back(), last_features, trails);
  }
  for (const auto& [id, track] : tracks) {
    if (track.size() < 3) continue;
    const Eigen::Vector3d p_W = triangulate(track);
    for (const auto& [k, uv] : track) {
      score.track_error_px.push_back((projectLeft(k, p_W) - uv).norm());
    }
  }
  return score;
}

TEST(FrontendTracking, SimTracksFollowTheirTrue3dPointsAndStereoHasTheTrueDisparity) {
  const SimSequence& seq = simSequence();
  for (bool predict : {false, true}) {
    SCOPED_TRACE(predict ? "with rotation prediction" : "without prediction");
    const TruthScore s = runAndScore(seq.left, seq.right, predict);
    EXPECT_EQ(s.lost_frames, 0);
    EXPECT_GT(s.min_tracked, 100);
    ASSERT_GT(s.track_error_px.size(), 1000u);
    EXPECT_LT(median(s.track_error_px), 0.5);
    EXPECT_LT(s.outlierShare(s.track_error_px, 2.0), 0.03);
    EXPECT_GT(s.stereo_matched, 0.7 * s.features);
    ASSERT_GT(s.stereo_error_px.size(), 1000u);
    EXPECT_LT(median(s.stereo_error_px), 0.3);
    // Corners on silhouettes have no single true depth (the ray cast hits one side): a few %.
    EXPECT_LT(s.outlierShare(s.stereo_error_px, 1.0), 0.05);
    // ~36 px of parallax over the run: keyframes beyond the first, not every frame.
    EXPECT_GE(s.keyframes, 2);
    EXPECT_LT(s.keyframes, kFrames / 2);
    std::printf(
        "predict %d: median track error %.3f px, >2 px %.2f %%, median stereo error "
        "%.3f px, stereo matched %.0f %%, keyframes %d, appearance rej %d geo rej %d\n",
        predict, median(s.track_error_px), 100 * s.outlierShare(s.track_error_px, 2.0),
        median(s.stereo_error_px), 100.0 * s.stereo_matched / s.features, s.keyframes,
        s.rejected_appearance, s.rejected_geometry);
  }
}

TEST(FrontendTracking, PatchMovingAgainstTheSceneIsRejectedGeometrically) {
  // An 90x90 block of frame 0 pasted into every left image, sliding down 4 px per frame while
  // the scene flows sideways: KLT follows it, the epipolar geometry does not.
  const SimSequence& seq = simSequence();
  std::vector<cv::Mat> left;
  const cv::Rect source(150, 120, 90, 90);
  for (int k = 0; k < kFrames; ++k) {
    left.push_back(seq.left[k].clone());
    seq.left[0](source).copyTo(left.back()(cv::Rect(380, 150 + 4 * k, 90, 90)));
  }
  const TruthScore clean = runAndScore(seq.left, seq.right, false);
  const TruthScore s = runAndScore(left, seq.right, false, "frontend_sim_patch.png");
  EXPECT_EQ(s.lost_frames, 0);
  EXPECT_LT(s.outlierShare(s.track_error_px, 2.0), 0.03);
  EXPECT_LT(median(s.track_error_px), 0.5);
  EXPECT_GT(s.rejected_geometry, clean.rejected_geometry + 2 * kFrames);
  std::printf("rejected geometrically: %d with the patch, %d without\n", s.rejected_geometry,
              clean.rejected_geometry);
}

TEST(FrontendTracking, GyroPredictionCarriesMonoTracksThroughAFastTurn) {
  // 6 degrees of yaw per frame (~48 px of flow, near KLT's capture range) while sliding 2 cm.
  const SimSequence& seq = simSequence();
  sim::GreyCameraConfig config;
  config.intrinsics = intrinsics();
  config.threads = 2;
  const sim::GreyCamera camera(config);
  const auto turnPose = [](int k) {
    Eigen::Isometry3d T = leftPose(0);
    T.translation().x() += 0.02 * k;
    T.linear() = Eigen::AngleAxisd(0.105 * k, Eigen::Vector3d::UnitZ()) * T.linear();
    return T;
  };
  constexpr int kTurnFrames = 6;
  std::vector<cv::Mat> images;
  for (int k = 0; k < kTurnFrames; ++k) {
    images.push_back(toMat(camera.render(seq.scene, turnPose(k), sim::Lighting{}, 7 + k).eyes[0]));
  }
  int tracked[2] = {0, 0};
  for (bool predict : {false, true}) {
    FeatureTracker tracker(simRig().left, FrontendConfig{});
    EXPECT_FALSE(tracker.isStereo());
    std::map<std::uint64_t, std::vector<std::pair<int, Eigen::Vector2d>>> tracks;
    for (int k = 0; k < kTurnFrames; ++k) {
      std::optional<Eigen::Matrix3d> R;
      if (predict && k > 0) R = turnPose(k).linear().transpose() * turnPose(k - 1).linear();
      const FrameFeatures frame = tracker.process(stamp(k), images[k], R);
      EXPECT_EQ(frame.stats.stereo_matched, 0);
      tracked[predict] += frame.stats.tracked;
      for (const FeatureObservation& f : frame.features) {
        EXPECT_FALSE(f.uv_right_px.has_value());
        tracks[f.track_id].emplace_back(k, f.uv_left_px);
      }
    }
    if (!predict) continue;
    // The predicted run's tracks follow their 3D points (poses of this run, not leftPose).
    std::vector<double> errors;
    for (const auto& [id, track] : tracks) {
      if (track.size() < 3) continue;
      Eigen::MatrixXd A(2 * track.size(), 4);
      for (std::size_t i = 0; i < track.size(); ++i) {
        const Eigen::Matrix<double, 3, 4> P =
            turnPose(track[i].first).inverse().matrix().topRows<3>();
        const Eigen::Vector2d xy = simRig().left.undistort(track[i].second);
        A.row(2 * i) = xy.x() * P.row(2) - P.row(0);
        A.row(2 * i + 1) = xy.y() * P.row(2) - P.row(1);
      }
      const Eigen::Vector3d p_W =
          Eigen::JacobiSVD<Eigen::MatrixXd>(A, Eigen::ComputeFullV).matrixV().col(3).hnormalized();
      for (const auto& [k, uv] : track) {
        const Eigen::Vector3d p_C = turnPose(k).inverse() * p_W;
        errors.push_back((simRig().left.projectPoint(p_C) - uv).norm());
      }
    }
    ASSERT_GT(errors.size(), 300u);
    EXPECT_LT(median(errors), 0.5);
  }
  // Over 5 tracked frames of 180 tracks (~8 % leave the view per frame at this rate): the
  // prediction keeps most, a zero-motion start about half as many.
  EXPECT_GT(tracked[1], 0.7 * 5 * 180);
  EXPECT_GT(tracked[1], tracked[0] + 100);
  std::printf("fast turn: %d track continuations with the gyro prediction, %d without\n",
              tracked[1], tracked[0]);
}

// ---------------------------------------------------------------------------------------------
// Bad input

template <typename F>
void expectInputError(F f, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "no InputError; expected one containing '" << fragment << "'";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(FrontendTracking, BadImagesAndTimestampsAreInputErrorsNamingTheProblem) {
  FeatureTracker tracker(simRig(), FrontendConfig{});
  const cv::Mat good(kHeight, kWidth, CV_8UC1, cv::Scalar(100));
  expectInputError([&] { tracker.process(1, cv::Mat(kHeight, kWidth - 2, CV_8UC1), good); },
                   "sim left image is 750x480 px but the calibration is 752x480 px");
  expectInputError([&] { tracker.process(1, good, cv::Mat()); }, "sim right image is empty");
  expectInputError([&] { tracker.process(1, cv::Mat(kHeight, kWidth, CV_8UC3), good); },
                   "3 channels");
  expectInputError([&] { tracker.process(1, cv::Mat(kHeight, kWidth, CV_16UC1), good); },
                   "16-bit unsigned");
  tracker.process(10, good, good);
  expectInputError([&] { tracker.process(10, good, good); }, "does not follow");
  // A featureless frame after a textured one loses every track, and says so.
  FeatureTracker textured(simRig(), FrontendConfig{});
  const SimSequence& seq = simSequence();
  EXPECT_FALSE(textured.process(1, seq.left[0], seq.right[0]).stats.lost);
  const FrameFeatures flat = textured.process(2, good, good);
  EXPECT_TRUE(flat.stats.lost);
  EXPECT_TRUE(flat.is_keyframe);
  EXPECT_EQ(flat.stats.tracked, 0);
}

// ---------------------------------------------------------------------------------------------
// EuRoC V1_01 excerpt (still vehicle). NOTE: a minimal local parse of sensor.yaml and data.csv,
// only what this test needs; the project's EuRoC reader replaces it when it lands.

std::vector<double> yamlNumbers(const std::string& text, const std::string& key) {
  const std::size_t at = text.find(key + ":");
  if (at == std::string::npos) throw InputError("sensor.yaml: no key '" + key + "'");
  const std::size_t open = text.find('[', at), close = text.find(']', open);
  std::string list = text.substr(open + 1, close - open - 1);
  std::replace(list.begin(), list.end(), ',', ' ');
  std::istringstream in(list);
  std::vector<double> values;
  for (double v; in >> v;) values.push_back(v);
  return values;
}

Camera readEurocCamera(const std::string& folder, const std::string& name) {
  std::ifstream file(folder + "/sensor.yaml");
  std::stringstream text;
  text << file.rdbuf();
  const std::string yaml = text.str();
  const std::vector<double> size = yamlNumbers(yaml, "resolution");
  const std::vector<double> k = yamlNumbers(yaml, "intrinsics");
  const std::vector<double> d = yamlNumbers(yaml, "distortion_coefficients");
  const std::vector<double> T = yamlNumbers(yaml.substr(yaml.find("T_BS")), "data");
  if (size.size() != 2 || k.size() != 4 || d.size() != 4 || T.size() != 16) {
    throw InputError(folder + "/sensor.yaml: unexpected list lengths");
  }
  Camera c;
  c.name = name;
  c.width_px = static_cast<int>(size[0]);
  c.height_px = static_cast<int>(size[1]);
  c.fx_px = k[0], c.fy_px = k[1], c.cx_px = k[2], c.cy_px = k[3];
  c.distortion = DistortionModel::kRadialTangential;
  c.coefficients = {d[0], d[1], d[2], d[3]};
  c.T_B_C.matrix() = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(T.data());
  return c;
}

std::vector<std::pair<std::int64_t, std::string>> readEurocImages(const std::string& folder) {
  std::ifstream csv(folder + "/data.csv");
  std::vector<std::pair<std::int64_t, std::string>> images;
  for (std::string line; std::getline(csv, line);) {
    if (line.empty() || line[0] == '#') continue;
    const std::size_t comma = line.find(',');
    std::string file = line.substr(comma + 1);
    file.erase(std::remove_if(file.begin(), file.end(), ::isspace), file.end());
    images.emplace_back(std::stoll(line.substr(0, comma)), folder + "/data/" + file);
  }
  return images;
}

TEST(FrontendTracking, EurocStillVehicleKeepsItsTracksAndMatchesStereo) {
  STRATA_REQUIRE_DATA("euroc_v101_micro/mav0", mav0);
  StereoCamera rig{readEurocCamera(mav0 + "/cam0", "cam0"),
                   readEurocCamera(mav0 + "/cam1", "cam1")};
  EXPECT_NEAR(rig.baseline_m(), 0.110, 0.002);  // the VI-sensor's published baseline
  const auto left = readEurocImages(mav0 + "/cam0");
  std::map<std::int64_t, std::string> right;  // cam1 lists a few more images than cam0
  for (const auto& [t, path] : readEurocImages(mav0 + "/cam1")) right[t] = path;
  ASSERT_GE(left.size(), 30u);
  FeatureTracker tracker(rig, FrontendConfig{});
  std::vector<double> flow, time_ms;
  int keyframes = 0, min_tracked = 1 << 30, min_stereo = 1 << 30, lost = 0;
  std::map<std::uint64_t, int> lengths;
  std::map<std::uint64_t, std::vector<Eigen::Vector2d>> trails;
  cv::Mat last_image;
  std::vector<FeatureObservation> last_features;
  std::map<std::uint64_t, Eigen::Vector2d> first_uv;  // tracks of frame 0
  std::vector<double> drift_px, stereo_share;
  for (int k = 0; k < 30; ++k) {
    ASSERT_EQ(right.count(left[k].first), 1u) << "no cam1 image at " << left[k].first;
    const cv::Mat l = cv::imread(left[k].second, cv::IMREAD_UNCHANGED);
    const cv::Mat r = cv::imread(right[left[k].first], cv::IMREAD_UNCHANGED);
    const FrameFeatures frame = tracker.process(left[k].first, l, r);
    keyframes += frame.is_keyframe;
    lost += frame.stats.lost;
    min_stereo = std::min(min_stereo, frame.stats.stereo_matched);
    if (k > 0) {
      flow.push_back(frame.stats.median_flow_px);
      min_tracked = std::min(min_tracked, frame.stats.tracked);
      time_ms.push_back(frame.stats.process_time_ms);
    }
    stereo_share.push_back(static_cast<double>(frame.stats.stereo_matched) / frame.features.size());
    last_image = l;
    last_features = frame.features;
    for (const FeatureObservation& f : frame.features) {
      trails[f.track_id].push_back(f.uv_left_px);
      lengths[f.track_id] = f.track_length;
      if (k == 0) first_uv[f.track_id] = f.uv_left_px;
      if (k == 29 && f.track_length == 30)
        drift_px.push_back((f.uv_left_px - first_uv[f.track_id]).norm());
    }
  }
  writeTrackFigure("frontend_euroc.png", last_image, last_features, trails);
  EXPECT_EQ(lost, 0);
  EXPECT_GT(min_tracked, 150);  // of the 180 targeted
  // The lower image is carpet (little texture) that the vehicle's body hides from cam1.
  EXPECT_GT(min_stereo, 60);
  // The vehicle stands still: frame-to-frame flow is KLT noise and does not add up over 30 frames.
  EXPECT_LT(median(flow), 0.3);
  EXPECT_LT(median(drift_px), 0.5);
  EXPECT_GT(median(stereo_share), 0.4);
  EXPECT_LE(keyframes, 4);  // only the 0.5 s interval rule fires over 1.5 s
  const int full_length = static_cast<int>(std::count_if(
      lengths.begin(), lengths.end(), [](const auto& kv) { return kv.second == 30; }));
  EXPECT_GT(full_length, 100);  // tracks that lived through all 30 frames
  std::printf(
      "EuRoC: min tracked %d, min stereo %d, median stereo share %.2f, median flow %.3f px, "
      "median drift over 30 frames %.3f px, %d keyframes, %d full tracks, median %.1f ms "
      "per stereo frame\n",
      min_tracked, min_stereo, median(stereo_share), median(flow), median(drift_px), keyframes,
      full_length, median(time_ms));
}

}  // namespace
}  // namespace strata::odometry
