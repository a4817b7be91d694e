#pragma once
// Pictures of a keyframe selection: the metrics along the trajectory with their
// thresholds and the selected keyframes, and a contact sheet of the selected images.
#include <cstdint>
#include <string>
#include <vector>

#include "strata/core/types.h"
#include "strata/select/keyframe_selection.h"

namespace strata::apps {

/// One panel per metric the method uses (ours: coverage, colour change, depth change; baselines:
/// the similarity), smoothed values as a curve, the threshold as a red line, triggered keyframes as
/// dots, and a strip under the panels marking the selected keyframes; with `truth` (one flag per
/// keyframe, from the simulator) a second strip marks the keyframes that truly see change.
ColorImage renderSelectionPlot(const selection::TrajectorySelection& selection,
                               const selection::SelectionConfig& config,
                               const std::vector<std::uint8_t>& truth = {});

/// Thumbnails (any equal size) in a grid, each labelled with its keyframe index; at most
/// `max_images` (evenly spread over the list when there are more).
ColorImage renderContactSheet(const std::vector<ColorImage>& thumbnails,
                              const std::vector<std::size_t>& labels, std::size_t max_images = 60);

/// A quarter-size copy (every 4th pixel of a 2x2 box average), for the contact sheet.
ColorImage thumbnail(const ColorImage& image);

}  // namespace strata::apps
