#pragma once
// The top-down pictures of `strata teach` and `strata repeat`: paths from above (x right, y up)
// over the world's room outlines, a legend, a 1-2-5 scale bar and caption lines.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "strata/sim/world/world.h"

namespace strata::apps {

struct PlotSeries {
  std::string label;
  std::array<int, 3> rgb = {0, 0, 0};
  std::vector<Eigen::Vector3f> points;  // drawn as a polyline, x and y only
  int thickness_px = 2;
};

/// Writes the PNG atomically (960 px wide). Error when it cannot be written.
void writeTopDownPng(const std::string& png_path, const sim::World& world,
                     const std::vector<PlotSeries>& series,
                     const std::vector<std::string>& caption);

}  // namespace strata::apps
