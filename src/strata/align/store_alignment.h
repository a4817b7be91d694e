#pragma once
// Alignment of the sessions in a map database (store/session_store.h): each session's frames
// are read from the folder it was imported from, its odometry from that folder's odometry file
// (odometry.txt, else groundtruth.txt, as the import took it), its keyframes and odometry edges
// from the store. The results go back into the store in one transaction, replacing any earlier
// alignment: features per keyframe, the verified loops as loop edges (accepted = kept by the
// pose graph), optimised keyframe poses and T_W_S of every aligned session.
// Errors: InputError naming the session for a folder that is gone or no longer matches the
// store (a keyframe without a frame within 20 ms, changed files), plus alignSessions' errors; the
// store is unchanged then. Thread safety: as Store.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "strata/align/alignment_eval.h"
#include "strata/align/session_alignment.h"
#include "strata/store/session_store.h"

namespace strata::align {

struct StoreAlignment {
  std::vector<store::SessionRecord> sessions;  // in id order, index-aligned with result.sessions
  std::vector<std::string> odometry_files;     // per session, absolute
  std::vector<std::vector<std::int64_t>> keyframe_ids;  // per session, per keyframe
  std::vector<std::unique_ptr<Dataset>> datasets;       // per session (poses: the odometry)
  AlignResult result;
};

/// The odometry file of a session folder: odometry.txt when present, else groundtruth.txt.
std::string sessionOdometryFile(const std::string& folder);

/// A stored session's frames from its folder (poses: its odometry file), after checking that the
/// folder is there and its files are those the import recorded: InputError naming the session
/// otherwise.
std::unique_ptr<Dataset> openStoredSession(store::Store& store, const store::SessionRecord& session);
/// The index of the frame within the import's 20 ms of a keyframe's timestamp (frame times
/// increasing); InputError naming the session when there is none (the folder changed).
std::size_t keyframeFrame(const std::vector<double>& frame_times_s, double keyframe_time_s,
                          const store::SessionRecord& session);

/// Aligns every session of `store` (the first by id anchors the world frame) and writes the
/// results into it.
StoreAlignment alignStore(store::Store& store, const AlignConfig& config = {},
                          const AlignProgress& progress = {});

/// The truth of every session's frames from its folder's groundtruth.txt (interpolated to each
/// frame's timestamp, 0.1 s at most from a truth pose), for scoreAlignment; nullopt when a session
/// has no such file or its odometry is that file (nothing to score against). InputError for a
/// truth file that does not parse.
std::optional<std::vector<SessionTruth>> loadStoreTruth(const StoreAlignment& alignment);

}  // namespace strata::align
