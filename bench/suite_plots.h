#pragma once
// The pictures of `strata-bench all`, built from the JSON reports of `strata-bench fuse`:
// per-kernel time per frame at each voxel size with Open3D beside it, time against map size, and
// the integration's fraction of the streaming ceiling. Missing fields draw as absent bars/points,
// so a report without the Open3D peer still plots.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "chart.h"

namespace strata::bench {

/// Per voxel size: Strata's median upload/normals/allocate/integrate (stacked, annotated with the
/// median wall time) and Open3D's median ms per frame (annotated with Strata wall / Open3D).
BarChart fuseKernelChart(const nlohmann::json& fuse_report);

/// Median device and wall ms per frame against blocks in the map, one point per report (each a
/// `fuse` report; the 2 cm result, or the first, of each), sorted by block count.
LineChart mapSizeChart(const std::vector<nlohmann::json>& fuse_reports, double voxel_size_m);

/// Integration bytes over the streaming ceiling, percent, per voxel size; 60 % dashed.
BarChart ceilingChart(const nlohmann::json& fuse_report);

/// Markdown table of a fuse report: per voxel size Strata wall/device ms, Open3D ms, ratio,
/// kernel medians and the ceiling fraction.
std::string fuseMarkdownTable(const nlohmann::json& fuse_report);

}  // namespace strata::bench
