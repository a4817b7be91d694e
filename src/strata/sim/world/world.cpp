#include "strata/sim/world/world.h"

#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>

#include "strata/core/error.h"
#include "strata/sim/rng.h"
#include "strata/sim/world/procedural_shapes.h"
#include "strata/sim/world/internal/layout.h"
#include "strata/sim/world/internal/scene_assets.h"
#include "strata/sim/world/shape_mesh.h"
#include "strata/sim/world/internal/static_geometry.h"
#include "strata/sim/world/internal/truth_builder.h"
#include "strata/sim/world/world_parser.h"

namespace strata::sim {

/// Embree scenes shared by every session (and by copies of the World), built on first use.
struct World::Cache {
  std::mutex mutex;
  std::shared_ptr<const SceneAssets> assets;
};

const char* shapeKindName(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::kBox:
      return "box";
    case ShapeKind::kCylinder:
      return "cylinder";
    case ShapeKind::kChair:
      return "chair";
    case ShapeKind::kTable:
      return "table";
    case ShapeKind::kShelf:
      return "shelf";
    case ShapeKind::kMesh:
      return "mesh";
    case ShapeKind::kVase:
      return "vase";
    case ShapeKind::kBlob:
      return "blob";
    case ShapeKind::kTube:
      return "tube";
    case ShapeKind::kLShape:
      return "l_shape";
    case ShapeKind::kUShape:
      return "u_shape";
    case ShapeKind::kStool:
      return "stool";
  }
  return "box";
}

namespace {

/// Builds an object's shape; a bad mesh file is reported at the object's line in the world file.
ShapeGeometry objectShape(const WorldSpec& spec, ObjectSpec& object) {
  if (isProceduralSeeded(object.shape.kind)) {
    object.shape.seed = hashCombine(spec.seed, object.shape.seed);
  }
  try {
    return buildShapeGeometry(object.shape);
  } catch (const InputError& e) {
    throw InputError(spec.source + ":" + std::to_string(object.line) + ": object '" + object.name +
                     "': " + e.what());
  }
}

}  // namespace

World World::load(const std::string& path) { return load(path, Options{}); }

World World::load(const std::string& path, const Options& options) {
  std::ifstream file(path);
  if (!file) throw InputError("cannot open world file '" + path + "'");
  std::stringstream text;
  text << file.rdbuf();
  const std::string base_dir = std::filesystem::path(path).parent_path().string();
  return fromYaml(text.str(), path, options, base_dir.empty() ? "." : base_dir);
}

World World::fromYaml(const std::string& text, const std::string& name_for_errors) {
  return fromYaml(text, name_for_errors, Options{});
}

World World::fromYaml(const std::string& text, const std::string& name_for_errors,
                      const Options& options, const std::string& base_dir) {
  World world;
  world.spec_ = parseWorldSpec(text, name_for_errors, base_dir);
  if (options.seed) world.spec_.seed = *options.seed;
  if (options.session_count) {
    if (*options.session_count < 1) throw InputError("session count must be at least 1");
    world.spec_.session_count = *options.session_count;
  }
  world.build();
  return world;
}

void World::build() {
  // Shapes first: loading a mesh file fills in its size, which the spec then carries.
  std::vector<ShapeGeometry> element_shapes;
  for (ObjectSpec& element : spec_.static_elements) {
    element_shapes.push_back(objectShape(spec_, element));
  }
  auto shapes = std::make_shared<std::vector<ShapeGeometry>>();
  for (auto* list : {&spec_.objects, &spec_.pool}) {
    for (ObjectSpec& object : *list) shapes->push_back(objectShape(spec_, object));
  }
  objects_ = spec_.objects;
  objects_.insert(objects_.end(), spec_.pool.begin(), spec_.pool.end());
  static_world_ = std::make_shared<const StaticWorld>(buildStaticWorld(spec_, element_shapes));

  LayoutInput input;
  input.spec = &spec_;
  for (const ShapeGeometry& shape : *shapes)
    input.half_footprints_m.push_back(shape.half_footprint_m);
  input.obstacles = static_world_->obstacles;
  input.door_zones = static_world_->door_zones;
  sessions_ = makeSessionTruths(spec_, objects_, generateLayouts(input));
  shapes_ = std::move(shapes);
  cache_ = std::make_shared<Cache>();
}

const SessionTruth& World::session(int index) const {
  if (index < 0 || index >= sessionCount()) {
    throw InputError("world '" + name() + "': session " + std::to_string(index) +
                     " does not exist (it has " + std::to_string(sessionCount()) + ")");
  }
  return sessions_[index];
}

void World::checkObjectId(int object_id) const {
  if (object_id < 1 || object_id > objectCount()) {
    throw InputError("world '" + name() + "': object id " + std::to_string(object_id) +
                     " does not exist (ids are 1.." + std::to_string(objectCount()) + ")");
  }
}

const ObjectSpec& World::object(int object_id) const {
  checkObjectId(object_id);
  return objects_[object_id - 1];
}

Mesh World::staticMesh() const {
  Mesh mesh;
  for (const StaticPart& part : static_world_->parts) {
    appendMesh(part.mesh, Eigen::Isometry3d::Identity(), part.material.albedo, mesh);
  }
  return mesh;
}

Mesh World::sessionMesh(int session_index) const {
  const SessionTruth& truth = session(session_index);
  Mesh mesh = staticMesh();
  for (const ObjectState& object : truth.objects) {
    if (!object.present) continue;
    for (const Mesh& part : (*shapes_)[object.id - 1].parts) {
      appendMesh(part, object.T_W_O, objects_[object.id - 1].material.albedo, mesh);
    }
  }
  return mesh;
}

Mesh World::objectMesh(int object_id) const {
  checkObjectId(object_id);
  Mesh mesh;
  for (const Mesh& part : (*shapes_)[object_id - 1].parts) {
    appendMesh(part, Eigen::Isometry3d::Identity(), objects_[object_id - 1].material.albedo, mesh);
  }
  return mesh;
}

Eigen::AlignedBox3d World::bounds() const {
  Eigen::AlignedBox3d box;
  for (const StaticPart& part : static_world_->parts) {
    for (const Eigen::Vector3f& v : part.mesh.vertices) box.extend(v.cast<double>());
  }
  return box;
}

std::unique_ptr<WorldScene> World::buildScene(int session_index,
                                              const WorldScene::Config& config) const {
  const SessionTruth& truth = session(session_index);
  std::shared_ptr<const SceneAssets> assets;
  {
    std::lock_guard<std::mutex> lock(cache_->mutex);
    if (!cache_->assets) {
      std::vector<Material> materials;
      for (const ObjectSpec& object : objects_) materials.push_back(object.material);
      cache_->assets = buildSceneAssets(*static_world_, *shapes_, materials);
    }
    assets = cache_->assets;
  }
  return std::make_unique<WorldScene>(std::move(assets), truth, config);
}

}  // namespace strata::sim
