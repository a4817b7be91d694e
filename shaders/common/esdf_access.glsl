// How the ESDF kernels reach the dense working box (uint cell per voxel, x fastest) and the voxel
// pools: through storage-buffer bindings when a buffer fits one binding's range (30-40 % faster
// on lavapipe than device addresses), else by device address (lavapipe binds at most 128 MiB).
// The host picks per buffer kind with specialization constants (engine/kernels/esdf_dispatch.cpp).
// Needs, before inclusion: map_layout.glsl, esdf_layout.glsl, a push-constant block `pc` and
//   ESDF_BOX_BINDING: the box's binding (pc.box_address);
//   ESDF_TSDF_POOL_BINDING (optional): the TSDF pool's binding (pc.tsdf_pool_address);
//   ESDF_ESDF_POOL_BINDING (optional): the ESDF pool's binding (pc.esdf_pool_address).
layout(constant_id = 0) const uint kBoxByAddress = 0u;
layout(constant_id = 1) const uint kPoolsByAddress = 0u;

layout(std430, binding = ESDF_BOX_BINDING) buffer EsdfBox { uint box_cells[]; };

uint loadBoxCell(uint64_t cell) {
  if (kBoxByAddress != 0u) return boxCell(pc.box_address, cell).value;
  return box_cells[uint(cell)];
}

void storeBoxCell(uint64_t cell, uint value) {
  if (kBoxByAddress != 0u) {
    boxCell(pc.box_address, cell).value = value;
  } else {
    box_cells[uint(cell)] = value;
  }
}

#ifdef ESDF_TSDF_POOL_BINDING
layout(std430, binding = ESDF_TSDF_POOL_BINDING) readonly buffer TsdfPool {
  TsdfVoxel tsdf_pool[];
};

TsdfVoxel loadTsdfVoxel(uint slot, uint v) {
  if (kPoolsByAddress != 0u) return tsdfBlock(pc.tsdf_pool_address, slot).voxels[v];
  return tsdf_pool[slot * uint(kVoxelsPerBlock) + v];
}
#endif

#ifdef ESDF_ESDF_POOL_BINDING
layout(std430, binding = ESDF_ESDF_POOL_BINDING) writeonly buffer EsdfPool {
  EsdfVoxel esdf_pool[];
};

void storeEsdfVoxel(uint slot, uint v, EsdfVoxel voxel) {
  if (kPoolsByAddress != 0u) {
    esdfBlock(pc.esdf_pool_address, slot).voxels[v] = voxel;
  } else {
    esdf_pool[slot * uint(kVoxelsPerBlock) + v] = voxel;
  }
}
#endif
