// Dynamic row masks, the form erosion and dilation work on: bit x of word slot * 64 + y + 8 z is
// set when voxel (x, y, z) of the block in `slot` is dynamic. A kernel invocation handles one row
// of 8 voxels with bit operations, reading the rows of the kernel^3 cube around it from the 3x3x3
// blocks around its block (no shared memory, no barriers: on lavapipe these cost more than the
// arithmetic). Needs map_layout.glsl, an `int neighbour_slots[]` buffer (27 per slot, neighbour n
// at block offset (n % 3, n / 3 % 3, n / 9) - 1, -1: unallocated), a specialization constant
// kKernel (odd, <= 7) and a function `uint maskRow(uint word)` reading the mask counted.

const int kRadius = kKernel / 2;
const uint kRowsPerBlock = 64u;

// Row (y, z) relative to the block in `slot` (y, z in [-kRadius, 8 + kRadius), so in the blocks
// around it) with the rows of its x-neighbours: bit j of the result is x = j - 8, x in [-8, 16).
// Unallocated blocks read as not dynamic.
uint extendedRow(uint slot, int y, int z) {
  int oy = (y + kBlockEdge) / kBlockEdge - 1;
  int oz = (z + kBlockEdge) / kBlockEdge - 1;
  uint row = uint((y - oy * kBlockEdge) + kBlockEdge * (z - oz * kBlockEdge));
  uint base = slot * 27u + uint(3 * (oy + 1) + 9 * (oz + 1));
  uint extended = 0u;
  for (uint ox = 0u; ox < 3u; ++ox) {
    int neighbour = neighbour_slots[base + ox];
    if (neighbour >= 0) extended |= maskRow(uint(neighbour) * kRowsPerBlock + row) << (8u * ox);
  }
  return extended;
}

// Bits of an extended row in the kernel-wide window centred on x (x in [0, 8)).
uint windowBits(uint extended, int x) {
  return (extended >> uint(x + kBlockEdge - kRadius)) & ((1u << uint(kKernel)) - 1u);
}
