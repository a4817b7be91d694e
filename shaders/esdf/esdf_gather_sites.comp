#version 450
// esdf_gather_sites: marks the sites of the listed blocks in the dense working box (the box was
// filled with kEsdfNoSite before). Site rule: engine/kernels/esdf_rules.h (isEsdfSite): observed
// (weight >= min_weight) and |tsdf| <= site threshold; a site cell holds offset (0, 0, 0).
// Workgroup: 8 x 8 x 8, one workgroup per listed block, one invocation per voxel.
// Bindings: 0 ivec4 blocks[] (xyz: block relative to the box in blocks, w: pool slot),
//           1 uint box cells[], 2 TsdfVoxel TSDF pool[]
//           (each by binding or by device address, esdf_access.glsl).
// Specialization: 0 kBoxByAddress, 1 kPoolsByAddress (esdf_access.glsl).
// Dispatch: (min(n, 65535), ceil(n / 65535)) groups for n listed blocks; extra groups exit.
// Push constants: EsdfBlockPush (engine/kernels/device_layout.h).
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"
#include "esdf_layout.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 8) in;

layout(std430, binding = 0) readonly buffer Blocks { ivec4 blocks[]; };

layout(push_constant, std430) uniform Push {
  uint64_t box_address;
  uint64_t tsdf_pool_address;
  uint64_t esdf_pool_address;
  uint box_nx;
  uint box_ny;
  uint box_nz;
  uint block_count;
  uint first_block;
  float voxel_size_m;
  float site_threshold_m;
  float min_weight;
  float max_distance_m;
  uint pad0;
} pc;

#define ESDF_BOX_BINDING 1
#define ESDF_TSDF_POOL_BINDING 2
#include "esdf_access.glsl"

void main() {
  uint group = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
  if (group >= pc.block_count) return;
  ivec4 listed = blocks[pc.first_block + group];
  ivec3 local = ivec3(gl_LocalInvocationID);
  uvec3 box_dims = uvec3(pc.box_nx, pc.box_ny, pc.box_nz);
  uint v = uint(local.x + kBlockEdge * (local.y + kBlockEdge * local.z));
  TsdfVoxel voxel = loadTsdfVoxel(uint(listed.w), v);
  if (voxel.weight >= pc.min_weight && abs(voxel.tsdf_m) <= pc.site_threshold_m) {
    storeBoxCell(boxCellOfVoxel(listed.xyz, local, box_dims), 0u);
  }
}
