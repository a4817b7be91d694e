#version 450
// change_difference: step 2, label D before clean-up: differenceLabel(S, M_N) per voxel.
// Reference: engine/kernels/change_reference.cpp (differenceReference); rule in change_rules.h.
// Workgroup: 256 x 1 x 1, one invocation per 4 voxels of the allocated slots (layers share slots,
// so voxel i of every layer is the same voxel).
// Bindings: 0 uint counters[] (counters[counter_index] += dynamic labels written), 1 S,
//           2 the session's TSDF layer, 3 the label layer written, 4 uint raw_mask[] (dynamic
//           row masks, zeroed by the host before; change_voxel_access.glsl).
// Specialization constant 0: layers by device address instead of bindings 1-3 (layers beyond
// one binding's range).
// Dispatch: (min(g, 65535), ceil(g / 65535)) groups for g = ceil(voxel_count / 1024).
// Push constants: ChangeVoxelPush (engine/kernels/change_layout.h): S and M TSDF layers, the raw
// label layer written.
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"
#include "change_layout.glsl"
#include "change_rules.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = 0) buffer Counters { uint counters[]; };

layout(push_constant, std430) uniform Push {
  uint64_t static_address;
  uint64_t session_address;
  uint64_t label_address;
  uint voxel_count;
  uint counter_index;
  float min_weight;
  float threshold_m;
  float merge_close_m;
  float max_weight;
} pc;

#include "change_voxel_access.glsl"
#include "change_count.glsl"

void main() {
  uint q = gl_GlobalInvocationID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x * 256u;
  uint dynamic_labels = 0u;
  if (4u * q < pc.voxel_count) {
    VoxelQuad s = loadStatic(q);
    VoxelQuad m = loadSession(q);
    uvec4 labels;
    for (int k = 0; k < 4; ++k) {
      labels[k] = differenceLabel(s.v[k], m.v[k], pc.min_weight, pc.threshold_m);
    }
    storeLabels(q, labels);
    markDynamic(q, labels);
    dynamic_labels = dynamicCount(labels);
  }
  countDynamic(dynamic_labels, pc.counter_index);
}
