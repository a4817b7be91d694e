// Hash lookup and trilinear TSDF sampling shared by the read-side kernels (raycast, later ESDF and
// reprojection). Needs, before inclusion: map_layout.glsl, a readonly `entries[]` binding, and a
// push-constant block `pc` with hash_mask, pool_address, voxel_size_m and min_weight.
// Mirrored by engine/kernels/tsdf_sampling.h.

// Pool slot of a block, or -1 when the block is not allocated.
int findBlockSlot(ivec3 block) {
  if (!blockInRange(block)) return -1;
  uint64_t key = packBlockKey(block);
  uint e = hashBlockKey(key) & pc.hash_mask;
  for (uint probe = 0u; probe < kMaxHashProbes; ++probe) {
    uint64_t seen = entries[e].key;
    if (seen == key) return int(entries[e].slot);
    if (seen == kEmptyBlockKey) return -1;
    e = (e + 1u) & pc.hash_mask;
  }
  return -1;
}

ivec3 blockOfVoxel(ivec3 v) { return ivec3(floor(vec3(v) / float(kBlockEdge))); }

// Voxel at a global index; false when unallocated or observed with weight below min_weight.
bool readVoxel(ivec3 v, out TsdfVoxel voxel) {
  ivec3 block = blockOfVoxel(v);
  int slot = findBlockSlot(block);
  if (slot < 0) return false;
  ivec3 local = v - block * kBlockEdge;
  voxel = tsdfBlock(pc.pool_address, uint(slot)).voxels[local.x + kBlockEdge * (local.y + kBlockEdge * local.z)];
  return voxel.weight >= pc.min_weight;
}

// Trilinear TSDF at p_W from the 8 surrounding voxel centres; false when any is unobserved.
bool sampleTsdf(vec3 p_W, out float tsdf_m) {
  vec3 g = p_W / pc.voxel_size_m - 0.5;
  ivec3 base = ivec3(floor(g));
  vec3 f = g - vec3(base);
  ivec3 block = blockOfVoxel(base);
  ivec3 far_block = blockOfVoxel(base + ivec3(1));
  float values[8];
  if (block == far_block) {
    // Common case: all 8 corners in one block, one hash lookup.
    int slot = findBlockSlot(block);
    if (slot < 0) return false;
    TsdfBlockRef ref = tsdfBlock(pc.pool_address, uint(slot));
    ivec3 l = base - block * kBlockEdge;
    for (int i = 0; i < 8; ++i) {
      ivec3 c = l + ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
      TsdfVoxel voxel = ref.voxels[c.x + kBlockEdge * (c.y + kBlockEdge * c.z)];
      if (!(voxel.weight >= pc.min_weight)) return false;
      values[i] = voxel.tsdf_m;
    }
  } else {
    for (int i = 0; i < 8; ++i) {
      TsdfVoxel voxel;
      if (!readVoxel(base + ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1), voxel)) return false;
      values[i] = voxel.tsdf_m;
    }
  }
  float x00 = mix(values[0], values[1], f.x);
  float x10 = mix(values[2], values[3], f.x);
  float x01 = mix(values[4], values[5], f.x);
  float x11 = mix(values[6], values[7], f.x);
  tsdf_m = mix(mix(x00, x10, f.y), mix(x01, x11, f.y), f.z);
  return true;
}
