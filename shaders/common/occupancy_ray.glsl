// Occupancy rays (allocation and mark passes): the push constants of both, the endpoints of a
// pixel's ray and the voxel traversal. Mirrors engine/kernels/occupancy_rules.h operation by
// operation (`precise`: no FMA contraction), so device and reference visit the same voxels.
// Push block mirrored by gpu::OccupancyRayPush in engine/kernels/occupancy_layout.h.

layout(push_constant, std430) uniform Push {
  mat4 T_W_C;
  vec4 K_inv;         // 1/fx, 1/fy, cx, cy
  uvec2 image_size;
  uint pixel_stride;  // every stride-th pixel on both axes casts a ray
  uint hash_mask;
  float min_depth_m;
  float max_range_m;
  float inv_voxel_size;
  uint frame_id;      // block stamps of the mark pass
  uint64_t state_address;  // state label layer (mark pass)
  uint walk_blocks;  // occupancy_allocate: 1 = step through blocks, 0 = through every voxel
  uint pad0;
} pc;

struct OccupancyRay {
  ivec3 voxel;
  ivec3 end_voxel;
  ivec3 step_dir;
  vec3 abs_delta;  // |end - origin| per axis
  // Next boundary crossings compared pairwise without division: t_i <= t_j <=> dist_i * |d_j| <=
  // dist_j * |d_i| (dist_i: from the origin to the next boundary on axis i). Pairs (x,y), (x,z),
  // (y,z): lhs = (dist_x |d_y|, dist_x |d_z|, dist_y |d_z|), rhs = (dist_y |d_x|, dist_z |d_x|,
  // dist_z |d_y|). A step on axis i moves its boundary by 1: its products grow by |d_j|.
  vec3 lhs;
  vec3 rhs;
  bool hit;
};

// False for an invalid sample; see occupancyRayEnds in occupancy_rules.h. `cell_scale` 1 walks
// voxels, 0.125 blocks: a power of two, so the scaled segment is exact and its cells contain the
// voxels' cells.
bool occupancyRayStart(vec2 uv, float depth_m, float cell_scale, out OccupancyRay ray) {
  // 0 marks a missing sample even when min_depth_m is 0; NaN fails every comparison.
  if (!(depth_m > 0.0 && depth_m >= pc.min_depth_m) || isinf(depth_m)) return false;
  precise float range = min(depth_m, pc.max_range_m);
  precise float x = ((uv.x - pc.K_inv.z) * pc.K_inv.x) * range;
  precise float y = ((uv.y - pc.K_inv.w) * pc.K_inv.y) * range;
  precise vec3 p_W = ((pc.T_W_C[0].xyz * x + pc.T_W_C[1].xyz * y) + pc.T_W_C[2].xyz * range) +
                     pc.T_W_C[3].xyz;
  precise vec3 end_vox = (p_W * pc.inv_voxel_size) * cell_scale;
  precise vec3 origin_vox = (pc.T_W_C[3].xyz * pc.inv_voxel_size) * cell_scale;
  ray.voxel = ivec3(floor(origin_vox));
  ray.end_voxel = ivec3(floor(end_vox));
  ray.step_dir = ivec3(sign(vec3(ray.end_voxel - ray.voxel)));
  precise vec3 abs_delta = abs(end_vox - origin_vox);
  precise vec3 dist = abs(vec3(ray.voxel + max(ray.step_dir, ivec3(0))) - origin_vox);
  precise vec3 lhs = dist.xxy * abs_delta.yzz;
  precise vec3 rhs = dist.yzz * abs_delta.xxy;
  ray.abs_delta = abs_delta;
  ray.lhs = lhs;
  ray.rhs = rhs;
  ray.hit = depth_m <= pc.max_range_m;
  return true;
}

// Steps to the next voxel; call only while ray.voxel != ray.end_voxel. The axis that crosses
// first among the open ones (not yet at the endpoint's coordinate) steps; ties go to the lower
// axis. Incremental, as Amanatides-Woo: three comparisons and two additions per step.
// NOTE: vector-wide without dynamic indexing: on lavapipe this loop is the kernels' cost. Adding
// 0.0 to the products that do not change is exact, so the selects below equal the reference's
// conditional additions.
void occupancyRayAdvance(inout OccupancyRay ray) {
  bvec3 open = notEqual(ray.voxel, ray.end_voxel);
  bvec3 first = lessThanEqual(ray.lhs, ray.rhs);
  bool x = open.x && (!open.y || first.x) && (!open.z || first.y);
  bool y = !x && open.y && (!open.z || first.z);
  bool z = !x && !y;
  vec3 d = ray.abs_delta;
  ray.lhs += vec3(x ? d.y : 0.0, x ? d.z : 0.0, y ? d.z : 0.0);
  ray.rhs += vec3(y ? d.x : 0.0, z ? d.x : 0.0, z ? d.y : 0.0);
  ray.voxel += (x ? ivec3(1, 0, 0) : (y ? ivec3(0, 1, 0) : ivec3(0, 0, 1))) * ray.step_dir;
}

// Pixel of invocation `id` on the strided grid; false outside the image.
bool occupancyPixel(uvec2 id, out uvec2 pixel) {
  pixel = id * pc.pixel_stride;
  return all(lessThan(pixel, pc.image_size));
}
