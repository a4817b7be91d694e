#pragma once
// A top-down picture of an estimated trajectory over the truth, after alignment: the truth in
// grey, the estimate in orange, error segments between matched poses, a 1-2-5 scale bar and the
// ATE in the caption. The view looks along the axis in which the truth extends least (world z for
// a ground robot or a hand-held sweep of a room).
#include <string>

#include "strata/trajectory/trajectory_error.h"

namespace strata::apps {

/// Writes the PNG atomically (960 px wide). Throws InputError when the error has no poses,
/// Error when the file cannot be written.
void writeTrajectoryPlot(const std::string& png_path, const trajectory::TrajectoryError& error);

}  // namespace strata::apps
