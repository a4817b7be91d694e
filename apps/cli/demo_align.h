#pragma once
// `strata demo --align`: the multi-session demo without shared poses. Each simulated session's
// odometry drifts (sim --drift) and is reported in a frame of its own (a random gravity-aligned
// offset, sim/sensors/odometry_frame.h); multi-session alignment (align/session_alignment.h)
// registers the sessions from their images and depth alone, and each aligned session is fused on
// its aligned poses. The common frame is the first session's odometry frame; for scoring against
// the world's truth the aligned poses are mapped into the truth's world by that session's true
// frame (one transform for all sessions, so nothing of the alignment is corrected by it).
// A session left unaligned is fused on its odometry mapped the same way (misregistered, counted).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "strata/align/alignment_eval.h"
#include "strata/core/progress.h"
#include "strata/sim/session/sim_session.h"

namespace strata::apps {

struct DemoAlignResult {
  std::size_t sessions = 0, aligned = 0;
  std::size_t loops_verified = 0, loops_accepted = 0;
  align::AlignmentScore score;  // against the simulator's truth
  double align_s = 0.0;         // the alignment, wall time
};

/// T * each pose (a session's poses moved into another frame), as replaceGivenPoses takes them.
std::vector<std::optional<Eigen::Isometry3d>> mapped(const Eigen::Isometry3d& T,
                                                     const std::vector<Eigen::Isometry3d>& poses);

/// Moves the sessions' (drifted) given poses into frames of their own, aligns them and replaces
/// the given poses as described above. Throws like alignSessions.
DemoAlignResult useAlignedPoses(const std::vector<std::shared_ptr<sim::SimSessionDataset>>& sessions,
                                bool quiet);

/// The result as a JSON object.
std::string demoAlignJson(const DemoAlignResult& result);
/// One sentence for the demo's summary.
std::string summarizeDemoAlign(const DemoAlignResult& result);

}  // namespace strata::apps
