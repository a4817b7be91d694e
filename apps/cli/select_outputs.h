#pragma once
// Files of `strata select`: the per-keyframe CSV, the plot and the contact sheet, written
// atomically.
#include <string>
#include <vector>

#include "strata/core/types.h"
#include "strata/select/keyframe_selection.h"
#include "strata/select/eval/selection_truth.h"

namespace strata::apps {

struct ScoredKeyframe {
  std::string name;
  double timestamp_s = 0.0;
  selection::KeyframeScore score;
  ColorImage thumbnail;  // quarter size; empty without colour
};

/// keyframes.csv: index, name, timestamp, raw and smoothed metrics, triggered, selected; with
/// `truth` (one per keyframe, from the simulator) also the true changed and unmapped pixel shares
/// and the true decision.
void writeSelectionCsv(const std::string& path, const std::vector<ScoredKeyframe>& keyframes,
                       const selection::TrajectorySelection& selection,
                       const std::vector<selection::KeyframeTruth>& truth = {});

/// selection.png and selected.png in `out_dir`; returns the paths written.
std::vector<std::string> writeSelectionPictures(const std::string& out_dir,
                                                const std::vector<ScoredKeyframe>& keyframes,
                                                const selection::TrajectorySelection& selection,
                                                const selection::SelectionConfig& config);

}  // namespace strata::apps
