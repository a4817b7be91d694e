#pragma once
// C++ reference of the change-detection passes (steps 2-5) on host maps: the readable
// specification of what shaders/change_*.comp compute, rule by rule from change_rules.h. A block
// missing from a map reads as unobserved (TSDF) or kUnknown (labels), as on the device, where
// every layer holds every block of the shared index.
#include "strata/change/change_config.h"
#include "strata/change/change_labels.h"
#include "strata/change/change_rules.h"
#include "strata/map/tsdf_map.h"

namespace strata::change {

/// Step 2: differenceLabel over the union of S's and M's blocks.
LabelMap differenceReference(const TsdfMap& s, const TsdfMap& m, const ChangeConfig& config);

/// Step 5 before clean-up: sessionDynamicLabel of session map `m` against S over both maps' blocks.
LabelMap sessionDynamicRawReference(const TsdfMap& m, const TsdfMap& s, const ChangeConfig& config);

/// Step 3, erosion: erodedLabel with the kernel^3 cube around every voxel of `raw`'s blocks.
LabelMap erodeReference(const LabelMap& raw, int kernel_voxels);

/// Step 3, dilation: dilatedLabel from the eroded labels' kernel^3 cube, over `raw`'s blocks.
LabelMap dilateReference(const LabelMap& raw, const LabelMap& eroded, int kernel_voxels,
                         DilationMask mask);

/// Step 3: erosion then dilation with the config's kernels.
LabelMap cleanLabelsReference(const LabelMap& raw, const ChangeConfig& config, DilationMask mask);

/// Step 4: S <- mergeStatic(S, M, D) on every block of M (allocated in S when absent).
void staticUpdateReference(TsdfMap& s, const TsdfMap& m, const LabelMap& d,
                           const ChangeConfig& config);

}  // namespace strata::change
