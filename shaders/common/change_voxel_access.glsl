// Voxel access of the per-voxel change kernels (difference, session dynamic, static update): one
// invocation per 4 consecutive voxels, read and written as 16-byte vectors (4 TSDF voxels of 12
// bytes are 3 vec4; 4 labels one uvec4): on lavapipe, wide accesses stream about twice as fast
// as 12-byte structs. Layers come through bindings 1-4, or by device address when a layer exceeds
// one binding's range (specialization constant 0; slower on lavapipe, where loads by address are
// split per lane). Needs map_layout.glsl and a push block `pc` with static_address,
// session_address and label_address. Quad q is voxels 4q..4q+3 of every layer (shared slots).

layout(constant_id = 0) const bool kByAddress = false;

layout(std430, binding = 1) buffer StaticLayer { vec4 static_layer[]; };
layout(std430, binding = 2) buffer SessionLayer { vec4 session_layer[]; };
layout(std430, binding = 3) buffer LabelLayer { uvec4 label_layer[]; };
// Dynamic row masks for erosion (change_rows.glsl): bit x of word i / 8 for voxel i.
layout(std430, binding = 4) buffer RawMask { uint raw_mask[]; };

layout(buffer_reference, std430, buffer_reference_align = 16) buffer Vec4s { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer UVec4s { uvec4 v[]; };

struct VoxelQuad {
  TsdfVoxel v[4];
};

VoxelQuad unpackQuad(vec4 a, vec4 b, vec4 c) {
  VoxelQuad quad;
  quad.v[0] = TsdfVoxel(a.x, a.y, floatBitsToUint(a.z));
  quad.v[1] = TsdfVoxel(a.w, b.x, floatBitsToUint(b.y));
  quad.v[2] = TsdfVoxel(b.z, b.w, floatBitsToUint(c.x));
  quad.v[3] = TsdfVoxel(c.y, c.z, floatBitsToUint(c.w));
  return quad;
}

VoxelQuad loadStatic(uint q) {
  if (kByAddress) {
    Vec4s layer = Vec4s(pc.static_address);
    return unpackQuad(layer.v[3u * q], layer.v[3u * q + 1u], layer.v[3u * q + 2u]);
  }
  return unpackQuad(static_layer[3u * q], static_layer[3u * q + 1u], static_layer[3u * q + 2u]);
}

VoxelQuad loadSession(uint q) {
  if (kByAddress) {
    Vec4s layer = Vec4s(pc.session_address);
    return unpackQuad(layer.v[3u * q], layer.v[3u * q + 1u], layer.v[3u * q + 2u]);
  }
  return unpackQuad(session_layer[3u * q], session_layer[3u * q + 1u],
                    session_layer[3u * q + 2u]);
}

void storeStatic(uint q, VoxelQuad quad) {
  TsdfVoxel v0 = quad.v[0], v1 = quad.v[1], v2 = quad.v[2], v3 = quad.v[3];
  vec4 a = vec4(v0.tsdf_m, v0.weight, uintBitsToFloat(v0.color_rgba), v1.tsdf_m);
  vec4 b = vec4(v1.weight, uintBitsToFloat(v1.color_rgba), v2.tsdf_m, v2.weight);
  vec4 c = vec4(uintBitsToFloat(v2.color_rgba), v3.tsdf_m, v3.weight, uintBitsToFloat(v3.color_rgba));
  if (kByAddress) {
    Vec4s layer = Vec4s(pc.static_address);
    layer.v[3u * q] = a;
    layer.v[3u * q + 1u] = b;
    layer.v[3u * q + 2u] = c;
  } else {
    static_layer[3u * q] = a;
    static_layer[3u * q + 1u] = b;
    static_layer[3u * q + 2u] = c;
  }
}

uvec4 loadLabels(uint q) { return kByAddress ? UVec4s(pc.label_address).v[q] : label_layer[q]; }

void storeLabels(uint q, uvec4 labels) {
  if (kByAddress) {
    UVec4s(pc.label_address).v[q] = labels;
  } else {
    label_layer[q] = labels;
  }
}

// Sets the raw row-mask bits of the quad's dynamic voxels (rare: dynamic voxels only). The 4
// voxels lie in one row (x = 4 (q % 2) .. + 3).
void markDynamic(uint q, uvec4 labels) {
  uvec4 bits = uvec4(equal(labels, uvec4(kLabelDynamic))) << uvec4(0u, 1u, 2u, 3u);
  uint row_bits = (bits.x | bits.y | bits.z | bits.w) << (4u * (q % 2u));
  if (row_bits != 0u) atomicOr(raw_mask[q / 2u], row_bits);
}

uint dynamicCount(uvec4 labels) {
  uvec4 dynamic_labels = uvec4(equal(labels, uvec4(kLabelDynamic)));
  return dynamic_labels.x + dynamic_labels.y + dynamic_labels.z + dynamic_labels.w;
}
