// Meshing: the generated marching-cubes table, extractMesh on analytic SDFs (sphere, box, random
// fields), PLY files and the Chamfer helper.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <set>
#include <tuple>

#include "strata/core/error.h"
#include "strata/mesh/extract_mesh.h"
#include "strata/mesh/mc_table.h"
#include "strata/mesh/mesh_metrics.h"
#include "strata/mesh/ply.h"

namespace strata {
namespace {

namespace fs = std::filesystem;
using Sdf = std::function<double(const Eigen::Vector3d&)>;

constexpr float kVoxel = 0.02f;
constexpr double kRadius = 0.3;
// Off-grid so no voxel centre sits exactly on the surface, and straddling block 0 on every axis.
const Eigen::Vector3d kCenter(0.0137, -0.0213, 0.0371);

/// Every voxel of the blocks covering [lo, hi] set from `sdf` (truncated), weight 1, colour
/// (varying, 100, 200).
TsdfMap makeSdfMap(const Sdf& sdf, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  MapConfig config;
  config.voxel_size_m = kVoxel;
  TsdfMap map(config);
  const double trunc = config.truncationDistance();
  const float block_m = config.blockSize();
  const BlockIndex b0 = (lo.cast<float>() / block_m).array().floor().cast<int>();
  const BlockIndex b1 = (hi.cast<float>() / block_m).array().floor().cast<int>();
  for (int bz = b0.z(); bz <= b1.z(); ++bz) {
    for (int by = b0.y(); by <= b1.y(); ++by) {
      for (int bx = b0.x(); bx <= b1.x(); ++bx) {
        const BlockIndex b(bx, by, bz);
        TsdfBlock& block = map.allocateBlock(b);
        for (int i = 0; i < kVoxelsPerBlock; ++i) {
          const Eigen::Vector3i local(i % 8, i / 8 % 8, i / 64);
          const Eigen::Vector3d p = voxelCenter(b * kBlockEdge + local, kVoxel).cast<double>();
          block[i].tsdf_m = static_cast<float>(std::clamp(sdf(p), -trunc, trunc));
          block[i].weight = 1.0f;
          block[i].color_rgba = packRgb(static_cast<std::uint8_t>(i % 256), 100, 200);
        }
      }
    }
  }
  return map;
}

double sphereSdf(const Eigen::Vector3d& p) { return (p - kCenter).norm() - kRadius; }

const Eigen::Vector3d kBoxHalf(0.25, 0.17, 0.29);
double boxSdf(const Eigen::Vector3d& p) {
  const Eigen::Vector3d q = (p - kCenter).cwiseAbs() - kBoxHalf;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

TsdfMap makeSphereMap() {
  return makeSdfMap(sphereSdf, kCenter.array() - 0.45, kCenter.array() + 0.45);
}

double enclosedVolume(const Mesh& m) {  // divergence theorem; positive when triangles face out
  double volume = 0.0;
  for (const Eigen::Vector3i& t : m.triangles) {
    const Eigen::Vector3d a = m.vertices[t[0]].cast<double>(), b = m.vertices[t[1]].cast<double>();
    volume += a.dot(b.cross(m.vertices[t[2]].cast<double>())) / 6.0;
  }
  return volume;
}

void expectClosedSurface(const Mesh& mesh) {
  const MeshTopology topology = analyzeTopology(mesh);
  EXPECT_TRUE(topology.isClosedOriented())
      << topology.boundary_edges << " boundary, " << topology.nonmanifold_edges << " non-manifold, "
      << topology.misoriented_edges << " misoriented edges";
  EXPECT_EQ(topology.euler_characteristic, 2);
  std::set<std::tuple<float, float, float>> unique;
  for (const auto& v : mesh.vertices) unique.insert({v.x(), v.y(), v.z()});
  EXPECT_EQ(unique.size(), mesh.vertices.size()) << "duplicate vertices";
  EXPECT_EQ(mesh.normals.size(), mesh.vertices.size());
  EXPECT_EQ(mesh.colors.size(), mesh.vertices.size());
}

// Which cube edges share a face: all four corners agree on one coordinate bit.
bool shareFace(int e0, int e1) {
  const CubeEdge a = cubeEdges()[e0], b = cubeEdges()[e1];
  for (int axis = 0; axis < 3; ++axis) {
    const int bit = (a.corner0 >> axis) & 1;
    if (((a.corner1 >> axis) & 1) == bit && ((b.corner0 >> axis) & 1) == bit &&
        ((b.corner1 >> axis) & 1) == bit)
      return true;
  }
  return false;
}

TEST(MeshCaseTable, EveryCaseIsBoundedByClosedLoopsOnTheCubeFacesWithoutFaceChords) {
  for (int config = 0; config < 256; ++config) {
    const McCase& mc = marchingCubesTable()[config];
    // Directed triangle edges; a fan's inner diagonals cancel, leaving the loops' boundary.
    std::multiset<std::pair<int, int>> boundary;
    for (int i = 0; i < mc.triangle_count; ++i) {
      for (int k = 0; k < 3; ++k) {
        const std::pair<int, int> e(mc.triangles[i][k], mc.triangles[i][(k + 1) % 3]);
        ASSERT_TRUE((mc.crossing_edges >> e.first) & 1) << "case " << config;
        const auto reverse = boundary.find({e.second, e.first});
        if (reverse == boundary.end()) {
          boundary.insert(e);
          continue;
        }
        boundary.erase(reverse);
        // An inner diagonal within a cube face could be shared with the cube across that face.
        EXPECT_FALSE(shareFace(e.first, e.second)) << "case " << config << ": face chord";
      }
    }
    std::array<int, kCubeEdges> starts{}, ends{};
    for (const auto& [from, to] : boundary) {
      EXPECT_TRUE(shareFace(from, to)) << "case " << config << ": segment leaves the face";
      ++starts[from];
      ++ends[to];
    }
    for (int e = 0; e < kCubeEdges; ++e) {
      const int crossing = (mc.crossing_edges >> e) & 1;
      EXPECT_EQ(starts[e], crossing) << "case " << config << " edge " << e;
      EXPECT_EQ(ends[e], crossing) << "case " << config << " edge " << e;
    }
  }
}

TEST(MeshCaseTable, EveryCaseFacesOutside) {
  // With vertices at edge midpoints, the patch and the inside parts of the cube faces close a
  // surface, so the patch's vector area equals the sum over faces of outward normal x outside area.
  for (int config = 1; config < 255; ++config) {
    const McCase& mc = marchingCubesTable()[config];
    auto midpoint = [](int e) {
      const CubeEdge& edge = cubeEdges()[e];
      Eigen::Vector3d p(edge.corner0 & 1, (edge.corner0 >> 1) & 1, (edge.corner0 >> 2) & 1);
      p[edge.axis] = 0.5;
      return p;
    };
    Eigen::Vector3d area = Eigen::Vector3d::Zero();
    for (int i = 0; i < mc.triangle_count; ++i) {
      const Eigen::Vector3d a = midpoint(mc.triangles[i][0]), b = midpoint(mc.triangles[i][1]);
      area += 0.5 * (b - a).cross(midpoint(mc.triangles[i][2]) - a);
    }
    Eigen::Vector3d expected = Eigen::Vector3d::Zero();
    for (int axis = 0; axis < 3; ++axis) {
      for (int side = 0; side < 2; ++side) {
        std::vector<int> out;  // outside corners of the face, as positions (u, v)
        for (int c = 0; c < 8; ++c)
          if (((c >> axis) & 1) == side && !((config >> c) & 1)) out.push_back(c);
        const bool opposite = out.size() == 2 && __builtin_popcount(out[0] ^ out[1]) == 2;
        // Outside area: corners cut off alone (1/8 each, also on ambiguous faces), or a half.
        const double outside_area[] = {0.0, 0.125, opposite ? 0.25 : 0.5, 0.875, 1.0};
        expected[axis] += (side ? 1.0 : -1.0) * outside_area[out.size()];
      }
    }
    EXPECT_LT((area - expected).norm(), 1e-12) << "case " << config;
  }
}

TEST(MeshExtract, SphereIsAccurateWatertightAndFacesOut) {
  const Mesh mesh = extractMesh(makeSphereMap());
  ASSERT_GT(mesh.triangles.size(), 1000u);
  expectClosedSurface(mesh);
  // The SDF is convex with curvature <= 1/(r - h) within h = 1 voxel of the surface, so its chord
  // over an edge lies at most h^2 / (8 (r - h)) above it (0.009 voxel here) and never below:
  // vertices lie on or just inside the sphere. 1e-6 m covers float rounding.
  const double bound = kVoxel * kVoxel / (8.0 * (kRadius - kVoxel));
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3d p = mesh.vertices[i].cast<double>();
    ASSERT_GE(sphereSdf(p), -bound - 1e-6);
    ASSERT_LE(sphereSdf(p), 1e-6);
    ASSERT_GT(mesh.normals[i].cast<double>().dot((p - kCenter).normalized()), 0.99);
    ASSERT_EQ(mesh.colors[i][1], 100);  // interpolating between equal colours keeps them
    ASSERT_EQ(mesh.colors[i][2], 200);
  }
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3f n = (mesh.vertices[t[1]] - mesh.vertices[t[0]])
                                  .cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    const Eigen::Vector3f out = mesh.vertices[t[0]] - kCenter.cast<float>();
    ASSERT_GE(n.dot(out), 0.0f) << "triangle faces inward";
  }
  EXPECT_NEAR(enclosedVolume(mesh) / (4.0 / 3.0 * M_PI * std::pow(kRadius, 3)), 1.0, 0.01);
}

TEST(MeshExtract, BoxIsAccurateWatertightAndFacesOut) {
  const Eigen::Vector3d margin = kBoxHalf + Eigen::Vector3d::Constant(0.15);
  const TsdfMap map = makeSdfMap(boxSdf, kCenter - margin, kCenter + margin);
  const Mesh mesh = extractMesh(map);
  expectClosedSurface(mesh);
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3d p = mesh.vertices[i].cast<double>();
    // Linear on the faces: exact away from the box's edges. Near them a 1-Lipschitz convex SDF's
    // chord over one voxel is off by at most half a voxel.
    Eigen::Vector3d q = (p - kCenter).cwiseAbs() - kBoxHalf;
    std::sort(q.data(), q.data() + 3);
    const bool near_edge = q[1] > -1.5 * kVoxel;
    ASSERT_LE(std::abs(boxSdf(p)), near_edge ? 0.5 * kVoxel : 1e-6) << p.transpose();
    ASSERT_GT(mesh.normals[i].cast<double>().dot(p - kCenter), 0.0);
  }
  EXPECT_NEAR(enclosedVolume(mesh) / (8.0 * kBoxHalf.prod()), 1.0, 0.02);
}

TEST(MeshExtract, RandomFieldsMeshWatertightAcrossBlocksAndAmbiguousFaces) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> value(-0.5f * kVoxel, 0.5f * kVoxel);
  for (int round = 0; round < 5; ++round) {
    TsdfMap map(MapConfig{});
    // 2x2x2 blocks of noise inside a positive border: every surface is closed.
    for (int i = 0; i < 8; ++i) {
      const BlockIndex b(i & 1, (i >> 1) & 1, i >> 2);
      TsdfBlock& block = map.allocateBlock(b);
      for (int v = 0; v < kVoxelsPerBlock; ++v) {
        const Eigen::Vector3i g = b * kBlockEdge + Eigen::Vector3i(v % 8, v / 8 % 8, v / 64);
        const bool border = (g.array() == 0).any() || (g.array() == 2 * kBlockEdge - 1).any();
        block[v] = {border ? kVoxel : value(rng), 1.0f, 0u};
      }
    }
    const Mesh mesh = extractMesh(map);
    const MeshTopology topology = analyzeTopology(mesh);
    EXPECT_GT(mesh.triangles.size(), 1000u);
    EXPECT_TRUE(topology.isClosedOriented())
        << topology.boundary_edges << " boundary, " << topology.nonmanifold_edges
        << " non-manifold, " << topology.misoriented_edges << " misoriented edges";
  }
}

TEST(MeshExtract, OutputDoesNotDependOnThreadCount) {
  const TsdfMap map = makeSphereMap();
  MeshOptions one;
  one.num_threads = 1;
  MeshOptions three;
  three.num_threads = 3;
  const Mesh a = extractMesh(map, one), b = extractMesh(map, three);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.colors, b.colors);
  EXPECT_EQ(a.triangles, b.triangles);
}

TEST(MeshExtract, UnobservedVoxelsProduceNothing) {
  TsdfMap map = makeSphereMap();
  MeshOptions strict;
  strict.min_weight = 2.0f;  // every voxel has weight 1
  EXPECT_TRUE(extractMesh(map, strict).vertices.empty());
  // Unobserve the half x > centre: only cubes with all corners at x <= centre may emit.
  for (const BlockIndex& index : map.sortedBlockIndices()) {
    TsdfBlock& block = *map.findBlock(index);
    for (int v = 0; v < kVoxelsPerBlock; ++v) {
      const Eigen::Vector3i g = index * kBlockEdge + Eigen::Vector3i(v % 8, v / 8 % 8, v / 64);
      if (voxelCenter(g, kVoxel).x() > kCenter.x()) block[v].weight = 0.0f;
    }
  }
  const Mesh half = extractMesh(map);
  ASSERT_FALSE(half.triangles.empty());
  for (const auto& p : half.vertices) EXPECT_LE(p.x(), kCenter.x());
  EXPECT_GT(analyzeTopology(half).boundary_edges, 0u);
}

TEST(MeshExtract, TruncationSeamIsNotMeshed) {
  // +trunc meets -trunc on a plane (as behind a thin wall): no surface by default.
  const float trunc = MapConfig{}.truncationDistance();
  const TsdfMap map =
      makeSdfMap([&](const Eigen::Vector3d& p) { return p.x() < 0.05 ? trunc : -trunc; },
                 Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(0.2));
  EXPECT_TRUE(extractMesh(map).triangles.empty());
  MeshOptions lenient;
  lenient.max_crossing_jump_truncations = 2.5f;
  EXPECT_FALSE(extractMesh(map, lenient).triangles.empty());
}

// A fresh directory per test, removed afterwards.
class MeshPly : public testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() / ("strata_test_mesh_" + std::to_string(getpid()) + "_" +
                                     testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::size_t fileCount() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), {}));
  }
  fs::path dir_;
};

void expectSameMesh(const Mesh& a, const Mesh& b) {
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.colors, b.colors);
  EXPECT_EQ(a.triangles, b.triangles);
}

TEST_F(MeshPly, WriteThenReadGivesTheSameMeshAndLeavesNoTemporaryFile) {
  const Mesh mesh = extractMesh(makeSphereMap());
  writePly(path("sphere.ply"), mesh);
  writePly(path("sphere.ply"), mesh);  // replaces the existing file
  EXPECT_EQ(fileCount(), 1u);
  expectSameMesh(readPly(path("sphere.ply")), mesh);

  Mesh bare;  // positions and faces only
  bare.vertices = mesh.vertices;
  bare.triangles = mesh.triangles;
  writePly(path("bare.ply"), bare);
  expectSameMesh(readPly(path("bare.ply")), bare);
}

TEST_F(MeshPly, ReadsAsciiWithExtraPropertiesAndPolygons) {
  std::ofstream(path("quad.ply")) << "ply\nformat ascii 1.0\ncomment hand made\n"
                                  << "element vertex 4\nproperty double x\nproperty double y\n"
                                  << "property double z\nproperty float quality\n"
                                  << "element face 1\nproperty list uchar uint vertex_indices\n"
                                  << "end_header\n0 0 0 9\n1 0 0 9\n1 1 0 9\n0 1 0 9\n4 0 1 2 3\n";
  const Mesh quad = readPly(path("quad.ply"));
  ASSERT_EQ(quad.vertices.size(), 4u);
  EXPECT_EQ(quad.vertices[2], Eigen::Vector3f(1, 1, 0));
  EXPECT_FALSE(quad.hasNormals());
  ASSERT_EQ(quad.triangles.size(), 2u);
  EXPECT_EQ(quad.triangles[1], Eigen::Vector3i(0, 2, 3));
}

TEST_F(MeshPly, TruncatedOrCorruptFilesThrowInputError) {
  writePly(path("good.ply"), extractMesh(makeSphereMap()));
  std::ifstream in(path("good.ply"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t header_end = bytes.find("end_header\n") + 11;
  const std::size_t cuts[] = {bytes.size() - 1, bytes.size() / 2, header_end, header_end - 5, 10};
  for (const std::size_t cut : cuts) {
    std::ofstream(path("cut.ply"), std::ios::binary) << bytes.substr(0, cut);
    EXPECT_THROW(readPly(path("cut.ply")), InputError) << "cut at " << cut;
  }
  std::ofstream(path("bad_index.ply"))
      << "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
      << "property float y\nproperty float z\nelement face 1\n"
      << "property list uchar int vertex_indices\nend_header\n"
      << "0 0 0\n3 0 0 1\n";
  EXPECT_THROW(readPly(path("bad_index.ply")), InputError);
  EXPECT_THROW(readPly(path("missing.ply")), InputError);
}

TEST_F(MeshPly, FailingWriteThrowsNamingThePathAndLeavesNothing) {
  const std::string target = path("no_such_dir/mesh.ply");
  try {
    writePly(target, extractMesh(makeSphereMap()));
    FAIL() << "writePly into a missing directory succeeded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(target), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("No such file or directory"), std::string::npos);
  }
  EXPECT_EQ(fileCount(), 0u);
}

double bruteForceChamfer(const Mesh& a, const Mesh& b) {
  auto mean_nearest = [](const Mesh& from, const Mesh& to) {
    double sum = 0.0;
    for (const auto& p : from.vertices) {
      float best = INFINITY;
      for (const auto& q : to.vertices) best = std::min(best, (p - q).squaredNorm());
      sum += std::sqrt(best);
    }
    return sum / from.vertices.size();
  };
  return 0.5 * (mean_nearest(a, b) + mean_nearest(b, a));
}

TEST(MeshChamfer, IsZeroForItselfAndTheShiftForAShiftedCopy) {
  const Mesh mesh = extractMesh(makeSphereMap());
  EXPECT_EQ(meshChamferDistance(mesh, mesh), 0.0);
  for (const float shift : {0.002f, 0.05f}) {
    Mesh moved = mesh;
    for (auto& v : moved.vertices) v += Eigen::Vector3f(shift, 0.0f, 0.0f);
    const double chamfer = meshChamferDistance(mesh, moved);
    EXPECT_NEAR(chamfer, bruteForceChamfer(mesh, moved), 1e-7);
    if (shift < 0.01f) {  // below the vertex spacing: each vertex's nearest is mostly its twin
      EXPECT_LE(chamfer, shift + 1e-6);
      EXPECT_GT(chamfer, 0.8 * shift);
    }
  }
  EXPECT_THROW(meshChamferDistance(mesh, Mesh{}), InputError);
}

}  // namespace
}  // namespace strata
