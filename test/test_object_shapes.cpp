// The simulator's procedural shapes (vase, blob, tube, l_shape, u_shape, stool) and the shapes
// world: deterministic from their seeds, closed meshes with outward normals filling their size,
// the world's seed mixed into the shapes' (held-out seeds give other shapes), and the symmetry the
// object database's evaluation gives them.
#include <gtest/gtest.h>

#include <map>
#include <utility>

#include "strata/core/error.h"
#include "strata/objects/eval/object_db_eval.h"
#include "strata/sim/world/procedural_shapes.h"
#include "strata/sim/world/world.h"
#include "strata/sim/world/world_paths.h"

namespace strata::sim {
namespace {

ShapeSpec shapeOf(ShapeKind kind, const Eigen::Vector3d& size, std::uint64_t seed = 1) {
  ShapeSpec shape;
  shape.kind = kind;
  shape.size_m = size;
  shape.seed = seed;
  return shape;
}

/// Every directed edge once and its reverse once: closed, consistently wound, no loose edge.
bool closedAndConsistent(const Mesh& mesh) {
  std::map<std::pair<int, int>, int> edges;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : edges) {
    if (count != 1) return false;
    const auto reverse = edges.find({edge.second, edge.first});
    if (reverse == edges.end() || reverse->second != 1) return false;
  }
  return true;
}

const ShapeKind kKinds[] = {ShapeKind::kVase,   ShapeKind::kBlob,   ShapeKind::kTube,
                            ShapeKind::kLShape, ShapeKind::kUShape, ShapeKind::kStool};

TEST(ProceduralShapes, ClosedOutwardAndFillingTheirSize) {
  const Eigen::Vector3d size(0.5, 0.4, 0.6);
  for (const ShapeKind kind : kKinds) {
    SCOPED_TRACE(shapeKindName(kind));
    const std::vector<Mesh> parts = proceduralParts(shapeOf(kind, size));
    ASSERT_FALSE(parts.empty());
    Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e9f), hi = -lo;
    double volume = 0.0;
    for (const Mesh& part : parts) {
      EXPECT_TRUE(closedAndConsistent(part));
      EXPECT_GT(signedVolume(part), 0.0);  // outward normals
      volume += signedVolume(part);
      for (const Eigen::Vector3f& v : part.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
    }
    // Footprint centred, bottom on the floor, the size's box filled exactly.
    EXPECT_NEAR(lo.z(), 0.0f, 1e-5f);
    EXPECT_NEAR(hi.z(), 0.6f, 1e-5f);
    EXPECT_NEAR(lo.x() + hi.x(), 0.0f, 1e-5f);
    EXPECT_NEAR(lo.y() + hi.y(), 0.0f, 1e-5f);
    EXPECT_NEAR(hi.x() - lo.x(), 0.5f, 1e-5f);
    EXPECT_NEAR(hi.y() - lo.y(), 0.4f, 1e-5f);
    // Solid, not a sliver, and not more than the box: 0.12 m^3 is the box; the thin stool is the
    // least (measured 0.0073 m^3), the U block the most (0.0827 m^3).
    EXPECT_GT(volume, 0.005);
    EXPECT_LT(volume, 0.12);
  }
}

TEST(ProceduralShapes, DeterministicAndSeedDependent) {
  const Eigen::Vector3d size(0.5, 0.5, 0.5);
  for (const ShapeKind kind : {ShapeKind::kVase, ShapeKind::kBlob, ShapeKind::kTube}) {
    SCOPED_TRACE(shapeKindName(kind));
    const Mesh a = proceduralParts(shapeOf(kind, size, 3)).front();
    const Mesh b = proceduralParts(shapeOf(kind, size, 3)).front();
    const Mesh c = proceduralParts(shapeOf(kind, size, 4)).front();
    ASSERT_EQ(a.vertices.size(), b.vertices.size());
    float same = 0.0f, other = 0.0f;
    for (std::size_t i = 0; i < a.vertices.size(); ++i) {
      same = std::max(same, (a.vertices[i] - b.vertices[i]).norm());
      other = std::max(other, (a.vertices[i] - c.vertices[i]).norm());
    }
    EXPECT_EQ(same, 0.0f);   // bit for bit
    EXPECT_GT(other, 0.02f);  // another seed moves some vertex by centimetres
  }
}

TEST(ProceduralShapes, BadSpecsAreRefused) {
  ShapeSpec stool = shapeOf(ShapeKind::kStool, {0.4, 0.4, 0.6});
  stool.legs = 2;
  EXPECT_THROW(proceduralParts(stool), InputError);
  ShapeSpec u = shapeOf(ShapeKind::kUShape, {0.6, 0.6, 0.6});
  u.thickness_m = 0.3;  // two arms of 0.3 leave no gap in 0.6
  EXPECT_THROW(proceduralParts(u), InputError);
  EXPECT_THROW(proceduralParts(shapeOf(ShapeKind::kBox, {0.4, 0.4, 0.4})), InputError);
  const std::string yaml =
      "rooms: [{min: [0, 0], max: [4, 4], height: 2.5}]\n"
      "objects:\n"
      "  - {name: u, type: u_shape, size: [0.6, 0.6, 0.5], thickness: 0.35}\n";
  try {
    World::fromYaml(yaml, "bad.yaml");
    ADD_FAILURE() << "thickness 0.35 in a 0.6 m U accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.yaml:3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("thickness"), std::string::npos) << e.what();
  }
}

TEST(ProceduralShapes, ShapesWorldMixesItsSeedIntoTheShapes) {
  World::Options held_out;
  held_out.seed = 12;
  const World develop = World::load(findWorld("shapes"));
  const World test = World::load(findWorld("shapes"), held_out);
  EXPECT_EQ(develop.seed(), 11u);
  ASSERT_EQ(develop.objectCount(), 13);
  int seeded = 0;
  for (int id = 1; id <= develop.objectCount(); ++id) {
    const ObjectSpec& a = develop.object(id);
    const ObjectSpec& b = test.object(id);
    SCOPED_TRACE(a.name);
    EXPECT_FALSE(develop.objectMesh(id).triangles.empty());
    if (isProceduralSeeded(a.shape.kind)) {
      ++seeded;
      EXPECT_NE(a.shape.seed, b.shape.seed);
      EXPECT_FALSE(eval::sameShape(a.shape, b.shape));
    } else {
      EXPECT_TRUE(eval::sameShape(a.shape, b.shape));
    }
  }
  EXPECT_EQ(seeded, 6);  // 2 vases, 3 blobs, 1 tube
  // The same file and seed: the same shapes.
  const World again = World::load(findWorld("shapes"));
  EXPECT_EQ(again.objectMesh(3).vertices, develop.objectMesh(3).vertices);
  // Objects move between sessions: every session after the first changes at least two.
  for (int s = 1; s < develop.sessionCount(); ++s) {
    int changed = 0;
    for (const ObjectState& o : develop.session(s).objects) {
      changed += o.since_previous != Change::kNone ? 1 : 0;
    }
    EXPECT_GE(changed, 2) << "session " << s;
  }
}

TEST(ProceduralShapes, EvaluationSymmetry) {
  ShapeSpec stool = shapeOf(ShapeKind::kStool, {0.4, 0.4, 0.6});
  stool.legs = 3;
  EXPECT_EQ(eval::yawSymmetryOrder(stool), 3);
  stool.size_m.y() = 0.3;
  EXPECT_EQ(eval::yawSymmetryOrder(stool), 1);  // elliptic seat, odd legs
  EXPECT_EQ(eval::yawSymmetryOrder(shapeOf(ShapeKind::kVase, {0.3, 0.3, 0.5})), 0);
  EXPECT_EQ(eval::yawSymmetryOrder(shapeOf(ShapeKind::kVase, {0.4, 0.3, 0.5})), 2);
  EXPECT_EQ(eval::yawSymmetryOrder(shapeOf(ShapeKind::kUShape, {0.8, 0.6, 0.5})), 1);
  EXPECT_EQ(eval::yawSymmetryOrder(shapeOf(ShapeKind::kBlob, {0.5, 0.5, 0.5})), 1);
}

}  // namespace
}  // namespace strata::sim
