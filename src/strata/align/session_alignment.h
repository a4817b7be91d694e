#pragma once
// Multi-session alignment: sessions recorded in their own odometry frames, drifting, registered
// into one world frame. Per keyframe ORB features with 3D from depth (keyframe_features.h) and a
// description of the surface its depth sees (surface_descriptor.h); candidates by appearance from
// the place index (place_index.h) and by surface descriptor, across sessions and, far enough
// apart in time, within one; each candidate verified geometrically (loop_verifier.h); then the
// multi-session pose graph (pose_graph.h) places the sessions and relaxes them. Every frame's
// pose follows from its keyframes' corrections. Method and figures: docs/align.md.
//
// Frames: S_k is session k's odometry frame (its frames' poses are T_S_C); W is the world frame,
// defined by the first session (T_W_S0 = identity, the anchor). T_W_C = T_W_S * T_S_C before
// relaxation; after it, each keyframe has its own T_W_C.
// Thread safety: one call at a time per set of inputs; the datasets' load() is called from the
// calling thread and from `threads` workers.
#include <Eigen/Geometry>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "strata/align/keyframe_features.h"
#include "strata/align/loop_verifier.h"
#include "strata/align/place_index.h"
#include "strata/align/pose_graph.h"
#include "strata/align/surface_descriptor.h"
#include "strata/core/dataset.h"

namespace strata::align {

/// One session: its frames (images loaded for the keyframes only), the session's odometry per
/// frame (T_S_C, camera-to-session) and which frames are keyframes.
struct AlignSession {
  std::string name;
  const Dataset* frames = nullptr;
  std::vector<double> frame_timestamps_s;         // per frame of `frames`, increasing
  std::vector<Eigen::Isometry3d> frame_T_S_C;     // per frame of `frames`
  std::vector<std::size_t> keyframes;  // indices into frames, increasing
  /// Information of the odometry edge keyframe k -> k+1 (size keyframes - 1), or empty: the
  /// pose graph's default.
  std::vector<store::Matrix6d> odometry_information;
  /// Stored features per keyframe (same order), when a store already has them (lifted with the
  /// keyframe's depth); empty or nullopt: extracted from the colour image.
  std::vector<std::optional<store::FeatureSet>> stored_features;
};

/// A session whose every frame is a keyframe, with the dataset's own poses (FrameStamp::T_W_C)
/// as its odometry: what a recorded or simulated folder with poses offers. `frames` (default:
/// `dataset`) gives the images; it must have as many frames and outlive the session's use.
AlignSession sessionFromDataset(const Dataset& dataset, const Dataset* frames = nullptr);

struct AlignConfig {
  FeatureConfig features;
  PlaceIndexConfig index;
  VerifyConfig verify;
  PoseGraphConfig graph;
  SurfaceConfig surface;
  std::size_t candidates_per_keyframe = 4;  // best-scored candidates verified per keyframe
  /// Also verified per keyframe: the admissible keyframes nearest by surface descriptor
  /// (surface_descriptor.h) that appearance did not propose; 0 leaves the surface out (no
  /// descriptors computed, the verifier's surface path off).
  std::size_t surface_candidates_per_keyframe = 3;
  int min_votes = 12;                       // candidates need this many descriptor votes
  /// Loops within a session join keyframes at least this far apart in time (closer ones are the
  /// odometry's business).
  double min_intra_session_gap_s = 15.0;
  bool intra_session_loops = true;
  int threads = 2;  // verification workers
  void validate() const;
};

/// A verified loop candidate (accepted by the verifier; the graph may still switch it off).
struct AlignLoop {
  std::size_t session_a = 0, keyframe_a = 0;  // keyframe: index into that session's keyframes
  std::size_t session_b = 0, keyframe_b = 0;
  LoopMeasurement measurement;
  double place_score = 0.0;
  double switch_value = 0.0;     // the graph's switch
  bool accepted = false;         // kept by the graph (both sessions aligned)
};

struct AlignStageTimes {
  double features_s = 0.0;      // extraction (or lifting) over all keyframes
  double retrieval_s = 0.0;     // index insertions and queries
  double verification_s = 0.0;  // wall time of all verifications
  double graph_s = 0.0;
  std::size_t keyframes = 0;
  std::size_t verifications = 0;
};

struct AlignedSession {
  bool aligned = false;
  std::optional<Eigen::Isometry3d> T_W_S;          // from the relaxed first keyframe
  std::vector<Eigen::Isometry3d> keyframe_T_W_C;   // per keyframe (empty when unaligned)
  /// Per frame of the session's dataset: the odometry corrected by its keyframes (empty when
  /// unaligned). A frame between keyframes k and k+1 takes T_W_C = C * T_S_C, with the
  /// correction C = T_W_Ck * T_S_Ck^-1 interpolated between the two keyframes' by time;
  /// frames before the first / after the last keyframe take that keyframe's correction.
  std::vector<Eigen::Isometry3d> frame_T_W_C;
  std::vector<Eigen::Isometry3d> frame_T_S_C;      // the odometry as given, per frame
  std::vector<double> frame_timestamps_s;
  std::vector<double> keyframe_timestamps_s;
  std::vector<std::size_t> keyframes;              // frame index of each keyframe
  std::vector<KeyframeFeatures> features;          // per keyframe (for the store)
};

struct AlignResult {
  std::vector<AlignedSession> sessions;
  std::vector<AlignLoop> loops;   // verified loops, in the order found
  std::size_t candidates = 0;     // candidates verified (accepted or not)
  std::vector<std::string> rejection_reasons;  // one per rejected candidate ("" trimmed)
  PoseGraphResult graph;
  AlignStageTimes times;
};

/// done of total for a named stage ("features", "loops", "graph").
using AlignProgress = std::function<void(const std::string& stage, std::size_t done,
                                         std::size_t total)>;

/// Aligns the sessions; the first anchors the world frame. InputError for no session, a session
/// without keyframes or frames, per-frame poses or timestamps whose count is not the frame
/// count, a non-finite pose, keyframe indices out of range or not increasing, keyframe images
/// that cannot be read (naming the session and frame).
AlignResult alignSessions(const std::vector<AlignSession>& sessions, const AlignConfig& config = {},
                          const AlignProgress& progress = {});

}  // namespace strata::align
