// Map layout shared by all map kernels; mirrored on the host in engine/kernels/device_layout.h
// (pinned there with static_assert). Block addressing mirrors engine/map/block_index.h.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_EXT_buffer_reference : require

const int kBlockEdge = 8;
const int kVoxelsPerBlock = 512;
const int kBlockCoordBias = 1 << 20;
const uint64_t kEmptyBlockKey = 0xFFFFFFFFFFFFFFFFul;
// Linear probing gives up after this many entries; the host then grows the table and retries.
const uint kMaxHashProbes = 128u;

// Hash table entry: a 63-bit block key, the block's pool slot, and the id of the last allocation
// pass that listed the block as touched (so each touched block is listed once per frame).
struct HashEntry {
  uint64_t key;
  uint slot;
  uint touched_stamp;
};

// Counters written by the allocation pass and read back by the host after it.
struct MapCounters {
  uint block_count;    // blocks ever allocated (slots handed out), may exceed pool capacity
  uint touched_count;  // blocks listed this pass, may exceed the touched-list capacity
  uint hash_failures;  // inserts that found no free entry within kMaxHashProbes
  uint reserved;
};

struct TsdfVoxel {
  float tsdf_m;
  float weight;
  uint color_rgba;
};

// The TSDF voxel pool, addressed by device address: it may exceed one binding's range (128 MiB on
// lavapipe), which a buffer reference does not care about.
layout(buffer_reference, std430, buffer_reference_align = 4) buffer TsdfBlockRef {
  TsdfVoxel voxels[kVoxelsPerBlock];
};

uint64_t packBlockKey(ivec3 b) {
  uint64_t x = uint64_t(b.x + kBlockCoordBias);
  uint64_t y = uint64_t(b.y + kBlockCoordBias);
  uint64_t z = uint64_t(b.z + kBlockCoordBias);
  return x | (y << 21) | (z << 42);
}

ivec3 unpackBlockKey(uint64_t key) {
  const uint64_t mask = (uint64_t(1) << 21) - 1;
  return ivec3(int(key & mask), int((key >> 21) & mask), int((key >> 42) & mask)) -
         ivec3(kBlockCoordBias);
}

uint hashBlockKey(uint64_t key) {
  uint lo = uint(key);
  uint hi = uint(key >> 32);
  uint h = (lo * 0x9E3779B1u) ^ (hi * 0x85EBCA77u);
  h ^= h >> 15;
  h *= 0x2C1B3C6Du;
  h ^= h >> 12;
  return h;
}

bool blockInRange(ivec3 b) {
  return all(greaterThanEqual(b, ivec3(-kBlockCoordBias))) && all(lessThan(b, ivec3(kBlockCoordBias)));
}

TsdfBlockRef tsdfBlock(uint64_t pool_address, uint slot) {
  return TsdfBlockRef(pool_address + uint64_t(slot) * uint64_t(kVoxelsPerBlock * 12));
}
