// Lists the models of an object database: the file `strata objects` (objects.sodb) or
// strata-mapper writes, or the copy a map database (.sqlite) holds. Per model its size, how many
// observations were merged into it and where each instance stood; with OUT_DIR, every model's
// mesh (model frame) as model_<id>.ply.   object_database DATABASE.sodb|MAP.sqlite [OUT_DIR]
#include <cstdio>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "strata/mesh/ply.h"
#include "strata/objects/object_database_file.h"
#include "strata/store/session_store.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: object_database DATABASE.sodb|MAP.sqlite [OUT_DIR]\n");
    return 2;
  }
  const std::string path = argv[1];
  try {
    strata::objects::ObjectDatabase database;
    if (path.size() > 7 && path.compare(path.size() - 7, 7, ".sqlite") == 0) {
      strata::store::StoreOptions options;
      options.create = false;
      strata::store::Store store(path, options);
      if (!strata::objects::loadObjectDatabase(store, database))
        throw std::runtime_error(path + " holds no object database");
    } else {
      database = strata::objects::loadObjectDatabase(path);
    }
    if (argc > 2) std::filesystem::create_directories(argv[2]);
    std::printf("%zu models over %zu sessions\n", database.models().size(),
                database.sessions().size());
    for (const strata::objects::ObjectModel& model : database.models()) {
      const Eigen::Vector3f& e = model.extent_m;
      std::printf("model %d: %.2f x %.2f x %.2f m, %.2f m2 of surface, %d observations merged\n",
                  model.id, e.x(), e.y(), e.z(), model.surface_area_m2, model.merged_observations);
      for (const strata::objects::ObjectInstance& instance : model.instances) {
        const Eigen::Vector3d p = instance.T_W_M.translation();
        std::printf("  session %d: at (%.2f, %.2f, %.2f) m, match score %.2f\n", instance.session,
                    p.x(), p.y(), p.z(), instance.match_score);
      }
      if (argc > 2) {
        strata::writePly(std::string(argv[2]) + "/model_" + std::to_string(model.id) + ".ply",
                         model.mesh_M);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "object_database: %s\n", e.what());
    return 1;
  }
  return 0;
}
