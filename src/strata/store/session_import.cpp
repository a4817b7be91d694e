#include "strata/store/session_import.h"

#include <filesystem>

#include "strata/core/error.h"
#include "strata/io/tum_format.h"

namespace strata::store {

namespace fs = std::filesystem;

namespace {

struct Frame {
  double timestamp_s = 0.0;
  Eigen::Isometry3d T_S_C;
  std::string depth_file, color_file;  // relative to the folder; "" when none
};

/// The session's frames: depth images with an odometry pose, or the odometry alone.
std::vector<Frame> readFrames(const fs::path& folder, const std::vector<tum::TimedPose>& poses) {
  std::vector<double> pose_times;
  for (const auto& p : poses) pose_times.push_back(p.timestamp_s);
  std::vector<tum::TimedFile> color;
  if (fs::exists(folder / "rgb.txt")) color = tum::readFileList((folder / "rgb.txt").string());
  const std::vector<double> color_times = tum::timestampsOf(color);
  std::vector<Frame> frames;
  if (!fs::exists(folder / "depth.txt")) {
    for (const auto& p : poses) frames.push_back({p.timestamp_s, p.T_W_C, "", ""});
    return frames;
  }
  for (const auto& d : tum::readFileList((folder / "depth.txt").string())) {
    const auto pose = tum::nearestWithin(pose_times, d.timestamp_s, tum::kMaxTimeDifference_s);
    if (!pose) continue;
    Frame f{poses[*pose].timestamp_s, poses[*pose].T_W_C, d.file, ""};
    if (const auto c = tum::nearestWithin(color_times, d.timestamp_s, tum::kMaxTimeDifference_s)) {
      f.color_file = color[*c].file;
    }
    // Two depth frames matched to one pose would give two keyframes at one time: keep the first.
    if (!frames.empty() && frames.back().timestamp_s == f.timestamp_s) continue;
    frames.push_back(std::move(f));
  }
  return frames;
}

std::vector<std::size_t> selectKeyframes(const std::vector<Frame>& frames, const ImportOptions& o) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (out.empty()) {
      out.push_back(i);
      continue;
    }
    const std::size_t last = out.back();
    const bool by_count =
        o.keyframe_every > 0 && i - last >= static_cast<std::size_t>(o.keyframe_every);
    const bool by_motion =
        o.keyframe_distance_m > 0 &&
        (frames[i].T_S_C.translation() - frames[last].T_S_C.translation()).norm() >=
            o.keyframe_distance_m;
    if (by_count || by_motion) out.push_back(i);
  }
  return out;
}

void checkOptions(const ImportOptions& o) {
  if (o.keyframe_every < 0 || !(o.keyframe_distance_m >= 0.0)) {
    throw InputError("import: --keyframe-every and --keyframe-distance-m must not be negative");
  }
  if (o.keyframe_every == 0 && o.keyframe_distance_m == 0.0) {
    throw InputError("import: set --keyframe-every or --keyframe-distance-m (both are off)");
  }
  if (!(o.odometry_sigma_m > 0.0) || !(o.odometry_sigma_rad > 0.0)) {
    throw InputError("import: odometry sigmas must be positive");
  }
}

}  // namespace

ImportResult importTumSession(Store& store, const std::string& folder_text,
                              const ImportOptions& options, const ImportProgress& progress) {
  checkOptions(options);
  const fs::path folder = fs::absolute(folder_text).lexically_normal();
  if (!fs::is_directory(folder)) {
    throw InputError("session folder '" + folder_text + "' does not exist");
  }
  ImportResult result;
  result.name = (folder.filename().empty() ? folder.parent_path() : folder).filename().string();
  if (const auto existing = store.findSessionBySource(folder.string())) {
    result.skipped = true;
    result.session_id = existing->id;
    return result;
  }
  const fs::path odometry =
      fs::exists(folder / "odometry.txt") ? folder / "odometry.txt" : folder / "groundtruth.txt";
  if (!fs::exists(odometry)) {
    throw InputError("session folder '" + folder_text +
                     "' has neither odometry.txt nor groundtruth.txt");
  }
  result.odometry_file = odometry.string();
  const std::vector<Frame> frames = readFrames(folder, tum::readTrajectory(odometry.string()));
  if (frames.empty()) {
    throw InputError("session folder '" + folder_text + "': no frame has an odometry pose in '" +
                     odometry.string() + "'");
  }
  const std::vector<std::size_t> chosen = selectKeyframes(frames, options);
  result.frames = frames.size();

  Transaction transaction = store.beginTransaction();
  result.session_id = store.addSession(result.name, folder.string());
  std::vector<KeyframeRecord> keyframes;
  for (std::size_t i : chosen) {
    KeyframeRecord k;
    k.session_id = result.session_id;
    k.timestamp_s = frames[i].timestamp_s;
    k.T_S_C = frames[i].T_S_C;
    keyframes.push_back(k);
  }
  const std::vector<std::int64_t> ids = store.addKeyframes(keyframes);
  Matrix6d information = Matrix6d::Zero();
  information.diagonal() << Eigen::Vector3d::Constant(1.0 / std::pow(options.odometry_sigma_m, 2)),
      Eigen::Vector3d::Constant(1.0 / std::pow(options.odometry_sigma_rad, 2));
  std::vector<EdgeRecord> edges;
  for (std::size_t j = 1; j < ids.size(); ++j) {
    EdgeRecord e;
    e.kind = EdgeKind::kOdometry;
    e.from_keyframe = ids[j - 1];
    e.to_keyframe = ids[j];
    e.T_from_to = keyframes[j - 1].T_S_C.inverse() * keyframes[j].T_S_C;
    e.information = information;
    edges.push_back(e);
  }
  result.edges = store.addEdges(edges).size();
  for (std::size_t j = 0; j < ids.size(); ++j) {
    const Frame& f = frames[chosen[j]];
    if (options.attach_images) {
      for (const auto& [file, kind] : {std::pair{f.depth_file, ResourceKind::kDepth},
                                       std::pair{f.color_file, ResourceKind::kColor}}) {
        if (file.empty()) continue;
        store.attachResource(result.session_id, ids[j], kind, (folder / file).string(),
                             AttachMode::kReference);
        ++result.resources;
      }
    }
    if (progress) progress(j + 1, ids.size());
  }
  transaction.commit();
  result.keyframes = ids.size();
  return result;
}

}  // namespace strata::store
