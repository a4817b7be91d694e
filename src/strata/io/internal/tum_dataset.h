#pragma once
// TUM RGB-D folder reader: rgb.txt, depth.txt, groundtruth.txt (+ optional camera.yaml).
#include <memory>
#include <string>

#include "strata/io/open_dataset.h"

namespace strata {

/// Defaults (TUM freiburg1-style): 640x480, fx=fy=525, cx=319.5, cy=239.5, 5000 units per metre.
/// Each depth frame takes the groundtruth pose nearest in time within 20 ms (frames without one are
/// dropped and counted in warnings()) and the rgb.txt image nearest within 20 ms (else no colour).
/// With options.trajectory_file the poses come from that file instead, and groundtruth.txt may be
/// absent. Depth files may be listed by absolute path. Throws InputError naming the file: missing
/// depth.txt/groundtruth.txt/trajectory file, malformed lines, a listed depth file that does not
/// exist, or no frame with a pose.
std::unique_ptr<Dataset> openTumDataset(const std::string& folder, const DatasetOptions& options);

}  // namespace strata
