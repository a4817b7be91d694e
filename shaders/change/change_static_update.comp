#version 450
// change_static_update: step 4, S <- mergeStatic(S, M_N, D) per voxel.
// Reference: engine/kernels/change_reference.cpp (staticUpdateReference); rule in change_rules.h.
// Workgroup: 256 x 1 x 1, one invocation per 4 voxels of the allocated slots; each voxel of S is
// read and written by its own invocation only.
// Bindings: 0 uint counters[] (unused; the per-voxel kernels share one layout), 1 S (read and
//           written), 2 M_N, 3 the label layer D, 4 unused (change_voxel_access.glsl).
// Specialization constant 0: layers by device address instead of bindings 1-3 (layers beyond
// one binding's range).
// Dispatch: (min(g, 65535), ceil(g / 65535)) groups for g = ceil(voxel_count / 1024).
// Push constants: ChangeVoxelPush (engine/kernels/change_layout.h): S (read and written), M_N,
// the label layer D (read).
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

void main() {
  uint q = gl_GlobalInvocationID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x * 256u;
  if (4u * q >= pc.voxel_count) return;
  VoxelQuad m = loadSession(q);
  // Most quads are unobserved in M_N (it covers part of the map): S stays as it is.
  bvec4 seen = bvec4(m.v[0].weight >= pc.min_weight, m.v[1].weight >= pc.min_weight,
                     m.v[2].weight >= pc.min_weight, m.v[3].weight >= pc.min_weight);
  if (!any(seen)) return;
  VoxelQuad s = loadStatic(q);
  uvec4 labels = loadLabels(q);
  for (int k = 0; k < 4; ++k) {
    s.v[k] = mergeStatic(s.v[k], m.v[k], labels[k], pc.min_weight, pc.merge_close_m,
                         pc.max_weight);
  }
  storeStatic(q, s);
}
