// ESDF layouts shared by the esdf_* kernels; mirrored on the host by engine/map/esdf_layer.h
// (EsdfVoxel, flag bits, offset packing), engine/kernels/esdf_plan.h (ListedBlock) and
// engine/kernels/device_layout.h (push constants). Needs map_layout.glsl first.

struct EsdfVoxel {
  float distance_m;
  uint site_and_flags;  // kEsdfObservedBit | kEsdfHasSiteBit | packed site offset
};

const uint kEsdfObservedBit = 1u << 31;
const uint kEsdfHasSiteBit = 1u << 30;
const int kEsdfOffsetBits = 10;
const uint kEsdfOffsetMask = (1u << kEsdfOffsetBits) - 1u;

// Working-box cell without a site within reach. Packed offsets use 30 bits, so it never collides.
const uint kEsdfNoSite = 0xFFFFFFFFu;

uint packSiteOffset(ivec3 o) {
  return (uint(o.x) & kEsdfOffsetMask) | ((uint(o.y) & kEsdfOffsetMask) << kEsdfOffsetBits) |
         ((uint(o.z) & kEsdfOffsetMask) << (2 * kEsdfOffsetBits));
}

ivec3 unpackSiteOffset(uint packed) {
  // bitfieldExtract on an int sign-extends the 10-bit two's complement fields.
  int p = int(packed);
  return ivec3(bitfieldExtract(p, 0, kEsdfOffsetBits),
               bitfieldExtract(p, kEsdfOffsetBits, kEsdfOffsetBits),
               bitfieldExtract(p, 2 * kEsdfOffsetBits, kEsdfOffsetBits));
}

uint squaredLength(ivec3 o) { return uint(o.x * o.x + o.y * o.y + o.z * o.z); }

// One cell of the dense working box (x fastest), reached by device address: the box may exceed a
// binding's range (128 MiB on lavapipe).
layout(buffer_reference, std430, buffer_reference_align = 4) buffer EsdfCellRef { uint value; };

EsdfCellRef boxCell(uint64_t box_address, uint64_t cell) {
  return EsdfCellRef(box_address + cell * 4ul);
}

layout(buffer_reference, std430, buffer_reference_align = 8) buffer EsdfBlockRef {
  EsdfVoxel voxels[kVoxelsPerBlock];
};

EsdfBlockRef esdfBlock(uint64_t pool_address, uint slot) {
  return EsdfBlockRef(pool_address + uint64_t(slot) * uint64_t(kVoxelsPerBlock * 8));
}

// Cell index of voxel `local` of a listed block (box-relative block coordinates) in the box.
uint64_t boxCellOfVoxel(ivec3 block_in_box, ivec3 local, uvec3 box_dims) {
  uvec3 v = uvec3(block_in_box * kBlockEdge + local);
  return uint64_t(v.x) +
         uint64_t(box_dims.x) * (uint64_t(v.y) + uint64_t(box_dims.y) * uint64_t(v.z));
}
