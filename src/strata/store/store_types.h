#pragma once
// The records of a map database (docs/store.md). Frames: S is a session's own odometry frame, W
// the shared world frame, C a camera; T_A_B maps points from frame B to frame A (metres).
// T_W_C = T_W_S * T_S_C.
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace strata::store {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// One mission, recorded in its own odometry frame S.
struct SessionRecord {
  std::int64_t id = 0;
  std::string name;
  std::string source_folder;  // absolute path of the imported folder (unique per map)
  double created_unix_s = 0.0;
  std::optional<Eigen::Isometry3d> T_W_S;  // session-to-world, nullopt until aligned
  bool aligned = false;
};

/// A keyframe of a session. Its id is set by the store (0 when handed in).
struct KeyframeRecord {
  std::int64_t id = 0;
  std::int64_t session_id = 0;
  double timestamp_s = 0.0;
  Eigen::Isometry3d T_S_C = Eigen::Isometry3d::Identity();  // odometry, camera-to-session
  std::optional<Eigen::Isometry3d> T_W_C;                   // optimised, camera-to-world
  /// Pose uncertainty, order (tx ty tz rx ry rz): metres and radians (rotation vector of a
  /// right-multiplied perturbation, T_S_C * Exp(delta)).
  std::optional<Matrix6d> covariance;
};

enum class EdgeKind { kOdometry, kLoop, kPrior };
const char* edgeKindName(EdgeKind kind);  // "odometry", "loop", "prior"

/// What a loop-closure check measured; present on loop edges only.
struct LoopStats {
  std::int64_t inliers = 0;
  double inlier_ratio = 0.0;  // inliers / candidate correspondences, in [0, 1]
  double residual = 0.0;      // RMS alignment residual of the inliers, metres
  bool accepted = false;
};

/// A pose-graph edge. Odometry and loop edges join two keyframes: T_from_to = T_X_from^-1 *
/// T_X_to in any frame X. A prior edge has no `to` keyframe; its T_from_to is the prior T_W_C of
/// `from`. The information matrix (inverse covariance) uses the covariance order above.
struct EdgeRecord {
  std::int64_t id = 0;
  EdgeKind kind = EdgeKind::kOdometry;
  std::int64_t from_keyframe = 0;
  std::optional<std::int64_t> to_keyframe;  // nullopt exactly for priors
  Eigen::Isometry3d T_from_to = Eigen::Isometry3d::Identity();
  Matrix6d information = Matrix6d::Identity();
  std::optional<LoopStats> loop;  // exactly for loops
};

/// Keypoints and descriptors of one keyframe. `format` names the detector/descriptor (e.g.
/// "orb"); every descriptor is `descriptor_bytes` long. Stored as one blob: `count` records of
/// float32 u_px, float32 v_px (little-endian, pixel centres at integers) then the descriptor.
struct FeatureSet {
  std::string format;
  std::uint32_t descriptor_bytes = 0;
  std::vector<Eigen::Vector2f> keypoints_px;
  std::vector<std::uint8_t> descriptors;  // keypoints_px.size() * descriptor_bytes
};

enum class ResourceKind { kDepth, kColor, kTsdfLayer };
const char* resourceKindName(ResourceKind kind);  // "depth", "color", "tsdf_layer"

/// A file belonging to a session (and, for images, a keyframe), at a path relative to the
/// database's folder, with its size and CRC-32 when attached.
struct ResourceRecord {
  std::int64_t id = 0;
  std::int64_t session_id = 0;
  std::optional<std::int64_t> keyframe_id;
  ResourceKind kind = ResourceKind::kDepth;
  std::string relative_path;
  std::uint64_t byte_size = 0;
  std::uint32_t crc32 = 0;
};

/// A resource whose file is not what was attached.
struct ResourceProblem {
  enum class Kind { kMissing, kSizeChanged, kChecksumChanged };
  ResourceRecord resource;
  Kind kind = Kind::kMissing;
  std::string message;  // names the file and what differs
};

/// The figures `strata map info` prints for one session.
struct SessionSummary {
  SessionRecord session;
  std::size_t keyframes = 0;
  std::size_t optimised_keyframes = 0;
  std::size_t odometry_edges = 0, loop_edges = 0, prior_edges = 0;
  std::size_t resources = 0;
  std::uint64_t resource_bytes = 0;
  double path_length_m = 0.0;  // along consecutive keyframes' T_S_C
  double first_timestamp_s = 0.0, last_timestamp_s = 0.0;
};

}  // namespace strata::store
