#pragma once
// A top-down picture of an alignment: left, each session's odometry as given (in its own frame,
// drawn in one set of axes: how far apart the frames start); right, the aligned trajectories in
// the common frame with the accepted loops (green) and those the pose graph switched off (red).
// One colour per session; unaligned sessions are named in the caption.
#include <string>

#include "strata/align/session_alignment.h"

namespace strata::apps {

/// Writes the PNG atomically. Error when the file cannot be written.
void writeAlignPlot(const std::string& png_path, const align::AlignResult& result,
                    const std::vector<std::string>& session_names);

}  // namespace strata::apps
