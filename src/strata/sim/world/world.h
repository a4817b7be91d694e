#pragma once
// A synthetic multi-session world: static rooms and furniture, movable objects whose layout changes
// from session to session, and the exact ground truth of every session (poses, changes, meshes,
// signed distance and occupancy through WorldScene). Loaded from a YAML world file (format:
// world_parser.h, worlds/README.md); fully determined by the file and its seed.
//
// Thread safety: a World is immutable after loading; every const method may be called from several
// threads at once.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "strata/mesh/mesh.h"
#include "strata/sim/world/session_truth.h"
#include "strata/sim/world/world_scene.h"
#include "strata/sim/world/world_spec.h"

namespace strata::sim {

struct SceneAssets;
struct ShapeGeometry;
struct StaticWorld;

class World {
 public:
  /// Overrides of the file's values (e.g. from the command line).
  struct Options {
    std::optional<std::uint64_t> seed;
    std::optional<int> session_count;  // >= 1
  };

  /// Reads a world file. InputError "path:line: field: what" for a bad file (see world_parser.h).
  static World load(const std::string& path, const Options& options);
  static World load(const std::string& path);
  /// Parses world text; `name_for_errors` prefixes messages, relative mesh paths resolve against
  /// `base_dir`.
  static World fromYaml(const std::string& text, const std::string& name_for_errors,
                        const Options& options, const std::string& base_dir = ".");
  static World fromYaml(const std::string& text, const std::string& name_for_errors);

  const std::string& name() const { return spec_.name; }
  std::uint64_t seed() const { return spec_.seed; }
  const WorldSpec& spec() const { return spec_; }

  int sessionCount() const { return static_cast<int>(sessions_.size()); }
  /// InputError for an index outside [0, sessionCount()).
  const SessionTruth& session(int index) const;

  /// Movable objects, ids 1..objectCount().
  int objectCount() const { return static_cast<int>(objects_.size()); }
  /// InputError for an id outside [1, objectCount()].
  const ObjectSpec& object(int object_id) const;

  /// Rooms, walls, floors, ceilings and static elements, world frame, coloured by albedo.
  Mesh staticMesh() const;
  /// The static mesh plus every object present in the session, world frame.
  Mesh sessionMesh(int session) const;
  /// One object's mesh in its own frame (footprint centred on the origin, bottom at z = 0).
  Mesh objectMesh(int object_id) const;
  /// Axis-aligned bounds of the static world (walls included).
  Eigen::AlignedBox3d bounds() const;

  /// The session as an Embree scene. The first call builds the shared static and per-object
  /// scenes (cached, thread safe); each call after that only instances the present objects.
  std::unique_ptr<WorldScene> buildScene(int session, const WorldScene::Config& config = {}) const;

 private:
  struct Cache;
  World() = default;
  void build();
  void checkObjectId(int object_id) const;

  WorldSpec spec_;
  std::vector<ObjectSpec> objects_;  // spec_.objects then spec_.pool: index = id - 1
  std::shared_ptr<const std::vector<ShapeGeometry>> shapes_;  // by object index
  std::shared_ptr<const StaticWorld> static_world_;
  std::vector<SessionTruth> sessions_;
  std::shared_ptr<Cache> cache_;  // Embree scenes, built on first use, shared by copies
};

}  // namespace strata::sim
