#pragma once
// The soak's figure: the mapper's resident memory (RSS, peak) over the run above its device
// memory, session ends as thin vertical lines (every n-th one when there are many). Pure: no I/O (writeChartPng writes it).
#include <opencv2/core.hpp>
#include <vector>

#include "soak_plateau.h"

namespace strata::bench {

/// 960x1080: two 960x540 line charts stacked.
cv::Mat drawSoakChart(const SoakSeries& series, const std::vector<double>& session_ends_s);

}  // namespace strata::bench
