#version 450
// view_gain: unknown volume a camera at each position would see, per yaw bin, for exploration.
// Each invocation marches one ray of the fan (engine/explore/view_gain.h states the model) in
// fixed point through the TSDF and adds the integer volume of the unknown samples it passes to
// its bin with a 64-bit atomic: integer sums do not depend on the order, so the result equals
// the reference's (viewGainReference, engine/explore/view_gain_reference.cpp, the same march).
// Blocks are found in a dense table of the box around the batch (view_gain_block_table.comp):
// on lavapipe a hash probe per block entered, with the lanes of a subgroup entering blocks at
// different steps, cost more than the rest of the march.
// Workgroup: 64 x 1 x 1; x: rays of one position (ray r = (bin * rays_per_bin + column) *
// elevation_rays + row, so neighbouring lanes march neighbouring rows of one column and read the
// same blocks); y + z * groups_y: the position (from position_offset).
// Bindings: 0 int block_slots[] (slot of each block of the box, -1: not allocated), 1 ivec4
// rays[] (x, y, z direction in 1/8192, w row), 2 int step_t[] (distance of each step in 1/256
// voxel), 3 uint step_weight[] (row * steps + step: volume units), 4 ivec4 origins[] (2 per
// position: voxel, fraction in 1/256), 5 uint64_t bin_units[] (position * bins + bin, zeroed by
// the host before), 6 TsdfVoxel pool[] (the TSDF layer, read through the binding when it fits one
// binding's range: faster on lavapipe; else by device address).
// Specialization constant 0: kPoolByAddress. Push constants: ViewGainPush
// (engine/explore/view_gain_kernel.cpp).
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer BlockSlots { int block_slots[]; };
layout(std430, binding = 1) readonly buffer Rays { ivec4 rays[]; };
layout(std430, binding = 2) readonly buffer StepT { int step_t[]; };
layout(std430, binding = 3) readonly buffer StepWeight { uint step_weight[]; };
layout(std430, binding = 4) readonly buffer Origins { ivec4 origins[]; };
layout(std430, binding = 5) buffer BinUnits { uint64_t bin_units[]; };
layout(std430, binding = 6) readonly buffer Pool { TsdfVoxel pool[]; };
layout(constant_id = 0) const uint kPoolByAddress = 0u;

layout(push_constant, std430) uniform Push {
  uint64_t pool_address;
  float min_weight;
  float occupied_below_m;  // half a voxel: observed voxels with tsdf below it stop a ray
  uint position_offset;
  uint position_count;     // of this dispatch
  uint groups_y;
  uint rays_per_position;
  uint bin_rays;
  uint yaw_bins;
  uint steps;
  int box_lo_x, box_lo_y, box_lo_z;  // the block table's box: first block, blocks per axis
  int box_nx, box_ny, box_nz;
} pc;

const int kFracBits = 8;
const int kDirBits = 13;

TsdfVoxel poolVoxel(int slot, ivec3 local) {
  uint v = uint(local.x + kBlockEdge * (local.y + kBlockEdge * local.z));
  if (kPoolByAddress != 0u) return tsdfBlock(pc.pool_address, uint(slot)).voxels[v];
  return pool[uint(slot) * uint(kVoxelsPerBlock) + v];
}

// Pool slot of a block, -1 when not allocated (or, never for a correct box, outside the box).
int blockSlot(ivec3 block) {
  ivec3 b = block - ivec3(pc.box_lo_x, pc.box_lo_y, pc.box_lo_z);
  ivec3 n = ivec3(pc.box_nx, pc.box_ny, pc.box_nz);
  if (any(lessThan(b, ivec3(0))) || any(greaterThanEqual(b, n))) return -1;
  return block_slots[b.x + n.x * (b.y + n.y * b.z)];
}

// The volume units ray `ray` sees from the position (voxel, frac). Same steps as marchRay in
// view_gain_reference.cpp.
uint64_t marchRay(ivec3 voxel, ivec3 frac, ivec4 ray) {
  uint weight_base = uint(ray.w) * pc.steps;
  uint64_t sum = 0ul;
  for (uint k = 0u; k < pc.steps; ++k) {
    ivec3 v = voxel + ((frac + ((ray.xyz * step_t[k]) >> kDirBits)) >> kFracBits);
    int slot = blockSlot(v >> 3);
    bool observed = false;
    float tsdf_m = 0.0;
    if (slot >= 0) {
      TsdfVoxel t = poolVoxel(slot, v & 7);
      observed = t.weight >= pc.min_weight;
      tsdf_m = t.tsdf_m;
    }
    if (!observed) {
      sum += uint64_t(step_weight[weight_base + k]);
    } else if (tsdf_m < pc.occupied_below_m) {
      break;
    }
  }
  return sum;
}

void main() {
  uint ray = gl_GlobalInvocationID.x;
  uint position = gl_WorkGroupID.y + gl_WorkGroupID.z * pc.groups_y;
  if (ray >= pc.rays_per_position || position >= pc.position_count) return;
  position += pc.position_offset;
  ivec3 voxel = origins[2u * position].xyz;
  ivec3 frac = origins[2u * position + 1u].xyz;
  uint64_t units = marchRay(voxel, frac, rays[ray]);
  if (units != 0ul) {
    atomicAdd(bin_units[position * pc.yaw_bins + ray / pc.bin_rays], units);
  }
}
