#version 450
// esdf_edt_pass: one axis of the exact Euclidean distance transform of the working box.
// Why this algorithm: the squared Euclidean distance is separable, d^2 = dx^2 + dy^2 + dz^2, so
// three 1-D passes (x, then y, then z) give the EXACT distance to the nearest site (Felzenszwalb &
// Huttenlocher 2012, "Distance Transforms of Sampled Functions", Alg. 1), in O(n) per line, with
// one independent line per invocation and a fixed number of passes. Propagating schemes are
// quasi-Euclidean (voxblox's 26-neighbour wavefront) or exchange values between blocks until
// nothing changes, a number of rounds that grows with the max distance; here the cost is three
// sweeps of the box whatever the distance.
// Each cell carries the offset to its nearest site (not only the distance): pass k takes the site
// candidate of the lowest parabola f(v) + (q - v)^2, f(v) = |offset(v)|^2, and adds (v - q) along
// the axis; the final offset points at an exact nearest site (ties broken arbitrarily).
// Distances beyond the reach (max_d2) are dropped in every pass: a nearest site within reach only
// ever goes through intermediate values within reach, so the capped result is still exact.
// Intersections are compared in 64-bit integers (exact, no float rounding). The x pass sees only
// sites (offset 0) and empty cells, so a forward and a backward sweep do it without the stack.
// Workgroup: 64 x 1 x 1, one invocation per line of this dispatch.
// Bindings: 0 uint box cells[] (esdf_access.glsl), 1 uvec2 scratch[]: per line, the lower
//   envelope's parabolas (position along the line, packed offset of that cell), entry k of line i
//   of the dispatch at k * line_count + i (the host keeps it within one binding's range).
// Specialization: 0 kBoxByAddress (esdf_access.glsl).
// Dispatch: (min(g, 65535), ceil(g / 65535)) groups for g = ceil(line_count / 64); lines are
//   (a, b) = (first_a + i % lines_a, first_b + i / lines_a) over the two other axes.
// Push constants: EsdfEdtPush (engine/kernels/device_layout.h).
#extension GL_GOOGLE_include_directive : require
#include "map_layout.glsl"
#include "esdf_layout.glsl"

layout(local_size_x = 64) in;

layout(push_constant, std430) uniform Push {
  uint64_t box_address;      // uint cells[], x fastest
  uint64_t reserved;
  uint line_count;           // lines in this dispatch
  uint first_line;           // index of its first line among all lines of the axis
  uint line_length;          // cells along the axis
  uint lines_a;              // lines along the first other axis (see Dispatch)
  uint stride_a;             // cell strides of a, of b and along the line
  uint stride_b;
  uint stride_line;
  uint axis;                 // 0 x, 1 y, 2 z
  uint max_d2;               // squared reach in voxels
  uint first_a;              // first line coordinates on the two other axes
  uint first_b;
  uint pad0;
} pc;

#define ESDF_BOX_BINDING 0
#include "esdf_access.glsl"

layout(std430, binding = 1) buffer Scratch { uvec2 scratch[]; };

uint64_t g_line_base;  // cell index of the line's first cell
uint g_local_line;     // line index within this dispatch

uint64_t cellAt(int q) { return g_line_base + uint64_t(q) * pc.stride_line; }
uint readCell(int q) { return loadBoxCell(cellAt(q)); }
void writeCell(int q, uint value) { storeBoxCell(cellAt(q), value); }
uvec2 loadEntry(int k) { return scratch[uint(k) * pc.line_count + g_local_line]; }
void storeEntry(int k, uvec2 entry) { scratch[uint(k) * pc.line_count + g_local_line] = entry; }

// An envelope entry with its apex cached: position v along the line, packed offset of that cell,
// and F = f(v) + v^2 with f(v) = |offset|^2, so intersections compare linearly.
struct Parabola {
  int v;
  uint packed;
  int64_t apex;
};

Parabola parabola(uvec2 entry) {
  int v = int(entry.x);
  return Parabola(v, entry.y, int64_t(squaredLength(unpackSiteOffset(entry.y))) + int64_t(v * v));
}

// True when parabola c (newest, rightmost) hides b between a and c: the intersection of (b, c)
// lies at or left of that of (a, b). Cross-multiplied, denominators positive.
bool hides(Parabola a, Parabola b, Parabola c) {
  return (c.apex - b.apex) * (b.v - a.v) <= (b.apex - a.apex) * (c.v - b.v);
}

// Lower envelope of the line's parabolas onto the scratch stack; returns the top index (-1: none).
int buildEnvelope() {
  int top = -1;
  Parabola below, last;  // entries top - 1 and top, cached
  for (int q = 0; q < int(pc.line_length); ++q) {
    uint packed = readCell(q);
    if (packed == kEsdfNoSite) continue;
    Parabola incoming = parabola(uvec2(uint(q), packed));
    while (top >= 1 && hides(below, last, incoming)) {
      --top;
      last = below;
      if (top >= 1) below = parabola(loadEntry(top - 1));
    }
    ++top;
    storeEntry(top, uvec2(uint(q), packed));
    below = last;
    last = incoming;
  }
  return top;
}

// Walks the envelope left to right and writes each cell's nearest site candidate.
void queryEnvelope(int top) {
  int j = 0;
  Parabola cur = parabola(loadEntry(0));
  Parabola next = top >= 1 ? parabola(loadEntry(1)) : cur;
  ivec3 unit = ivec3(pc.axis == 0u ? 1 : 0, pc.axis == 1u ? 1 : 0, pc.axis == 2u ? 1 : 0);
  for (int q = 0; q < int(pc.line_length); ++q) {
    // Advance while the next parabola is already lower at q (their intersection is left of q).
    while (j < top && next.apex - cur.apex < int64_t(2 * q * (next.v - cur.v))) {
      ++j;
      cur = next;
      if (j < top) next = parabola(loadEntry(j + 1));
    }
    ivec3 offset = unpackSiteOffset(cur.packed) + (cur.v - q) * unit;
    writeCell(q, squaredLength(offset) <= pc.max_d2 ? packSiteOffset(offset) : kEsdfNoSite);
  }
}

// The first pass (x): every cell is a site (offset 0) or kEsdfNoSite, so the nearest site along
// the line comes from a forward and a backward sweep, without the envelope's scratch.
void sweepLine() {
  int n = int(pc.line_length);
  int last = -1;
  for (int q = 0; q < n; ++q) {
    uint cell = readCell(q);
    if (cell == 0u) {
      last = q;
    } else if (last >= 0 && uint((q - last) * (q - last)) <= pc.max_d2) {
      writeCell(q, packSiteOffset(ivec3(last - q, 0, 0)));
    }
  }
  if (last < 0) return;  // no site on this line
  int next = -1;
  for (int q = n - 1; q >= 0; --q) {
    uint cell = readCell(q);
    if (cell == 0u) {  // forward results are never 0: their offset is non-zero
      next = q;
    } else if (next >= 0 && uint((next - q) * (next - q)) <= pc.max_d2 &&
               (cell == kEsdfNoSite || next - q < -unpackSiteOffset(cell).x)) {
      writeCell(q, packSiteOffset(ivec3(next - q, 0, 0)));
    }
  }
}

void main() {
  uint local_line = gl_GlobalInvocationID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x * 64u;
  if (local_line >= pc.line_count) return;
  uint line = pc.first_line + local_line;
  uint a = pc.first_a + line % pc.lines_a;
  uint b = pc.first_b + line / pc.lines_a;
  g_line_base = uint64_t(a) * pc.stride_a + uint64_t(b) * pc.stride_b;
  g_local_line = local_line;
  if (pc.axis == 0u) {
    sweepLine();
    return;
  }
  int top = buildEnvelope();
  if (top >= 0) queryEnvelope(top);
}
