// Fuses a TUM RGB-D folder (rgb.txt, depth.txt, groundtruth.txt) with strata::Mapper and writes
// the mesh as PLY.   fuse_tum DATASET_DIR [OUT.ply] [VOXEL_SIZE_M]
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "strata/core/error.h"
#include "strata/io/open_dataset.h"
#include "strata/mapper/mapper.h"
#include "strata/mesh/ply.h"
#include "strata/vk/vk.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: fuse_tum DATASET_DIR [OUT.ply] [VOXEL_SIZE_M]\n");
    return 2;
  }
  const std::string out = argc > 2 ? argv[2] : "mesh.ply";
  try {
    const auto dataset = strata::openDataset(argv[1], {});
    const auto context = strata::vk::Context::create();
    strata::MapperConfig config;
    config.map.voxel_size_m = argc > 3 ? std::strtof(argv[3], nullptr) : 0.02f;
    strata::Mapper mapper(config, *context);
    for (std::size_t i = 0; i < dataset->size(); ++i) {
      mapper.integrate(dataset->load(i), dataset->intrinsics());
    }
    const strata::Mesh mesh = mapper.mesh();
    strata::writePly(out, mesh);
    std::printf("fused %zu frames into %u blocks on %s; %zu triangles -> %s\n", dataset->size(),
                mapper.blockCount(), context->deviceName().c_str(), mesh.triangles.size(),
                out.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuse_tum: %s\n", e.what());
    return 1;
  }
  return 0;
}
