// Layout shared by the change-detection kernels (shaders/change_*.comp); the push constants are
// mirrored on the host in engine/kernels/change_layout.h, the label values in
// engine/kernels/change_labels.h. Needs map_layout.glsl first.

// VoxelLabel values; a label layer stores one uint per voxel, slot s at s * 512 (x fastest).
const uint kLabelUnknown = 0u;
const uint kLabelStatic = 1u;
const uint kLabelDynamic = 2u;

// DilationMask values (engine/kernels/change_rules.h).
const uint kMaskObserved = 0u;
const uint kMaskRawDynamic = 1u;

// A whole TSDF layer or label layer as one flat array, voxel i = slot * 512 + local index. By
// device address, so layers may exceed one binding's range (128 MiB on lavapipe).
layout(buffer_reference, std430, buffer_reference_align = 4) buffer TsdfVoxels {
  TsdfVoxel v[];
};
layout(buffer_reference, std430, buffer_reference_align = 4) buffer Labels {
  uint v[];
};
