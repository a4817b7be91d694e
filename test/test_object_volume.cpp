// Object observations, models and their merge on constructed sessions (object_volume_scene.h: a
// floor with one object, analytic distances): what an observation keeps, which segments it
// refuses, trilinear sampling, and the weighted SDF merge of two partial views.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>
#include <tuple>

#include "strata/core/error.h"
#include "strata/mesh/extract_mesh.h"
#include "object_volume_scene.h"
#include "strata/objects/object_model.h"
#include "strata/objects/object_observation.h"

namespace strata::objects {
namespace {

using test::kVoxel;

constexpr double kPi = 3.14159265358979323846;

const Eigen::AlignedBox3d kBox = test::footBox(0.4, 0.3, 0.4);
// Top and four sides above the floor.
const double kBoxVisibleAreaM2 = 0.4 * 0.3 + 2.0 * (0.4 + 0.3) * 0.4;

test::Sdf boxAt(const Eigen::Isometry3d& T_W_L) { return test::placedBox(kBox, T_W_L); }

const auto kEverywhere = [](const Eigen::Vector3d&) { return true; };

ObjectObservation observeOnly(const test::ObjectSession& s, int session) {
  return observeObject(s.map, s.surface, test::onlyObject(s), session);
}

/// Distance of a model-frame point to the scene's surface (floor or box), the box at T_M_L.
double sceneDistance(const Eigen::Vector3f& p_M, const Eigen::Isometry3d& T_L_M) {
  const Eigen::Vector3d p_L = T_L_M * p_M.cast<double>();
  return std::abs(std::min(p_L.z(), test::boxSdf(p_L, kBox)));
}

double meanSceneDistance(const Mesh& mesh, const Eigen::Isometry3d& T_L_M) {
  double sum = 0.0;
  for (const auto& v : mesh.vertices) sum += sceneDistance(v, T_L_M);
  return mesh.vertices.empty() ? 1e9 : sum / static_cast<double>(mesh.vertices.size());
}

/// The triangles of `mesh` whose three vertices pass `keep`, re-indexed.
Mesh subMesh(const Mesh& mesh, const std::function<bool(const Eigen::Vector3f&)>& keep) {
  Mesh out;
  std::map<int, int> index;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    bool all = true;
    for (int k = 0; k < 3; ++k) all = all && keep(mesh.vertices[static_cast<std::size_t>(t[k])]);
    if (!all) continue;
    Eigen::Vector3i tri;
    for (int k = 0; k < 3; ++k) {
      auto [it, inserted] = index.try_emplace(t[k], static_cast<int>(out.vertices.size()));
      if (inserted) {
        const auto i = static_cast<std::size_t>(t[k]);
        out.vertices.push_back(mesh.vertices[i]);
        if (mesh.hasNormals()) out.normals.push_back(mesh.normals[i]);
        if (mesh.hasColors()) out.colors.push_back(mesh.colors[i]);
      }
      tri[k] = it->second;
    }
    out.triangles.push_back(tri);
  }
  return out;
}

TEST(ObjectVolume, ObservationKeepsTheBoxBandAndNotTheFloor) {
  const Eigen::Isometry3d T_W_L = test::floorPose(0.8, 0.75, 0.0);
  const test::ObjectSession s = test::makeObjectSession(boxAt(T_W_L), kEverywhere, 1);
  const ObjectObservation obs = observeOnly(s, 1);
  EXPECT_EQ(obs.session, 1);
  EXPECT_EQ(obs.segment_id, s.objects[0].id);

  // O: world axes, origin at the centroid rounded to whole voxels.
  EXPECT_TRUE(obs.T_W_O.linear().isIdentity(0.0));
  const Eigen::Vector3d t = obs.T_W_O.translation();
  const Eigen::Vector3i offset = (t / kVoxel).array().round().cast<int>();
  EXPECT_LT((t - offset.cast<double>() * kVoxel).norm(), 1e-6);
  EXPECT_LE((t - s.objects[0].centroid.cast<double>()).cwiseAbs().maxCoeff(), 0.5 * kVoxel + 1e-6);

  // Every kept voxel is copied unchanged and lies in the box's band (4 voxels), none out on the
  // floor; the floor the box stands on is left out.
  const double band_m = 4.0 * kVoxel;
  std::size_t kept = 0, far_from_box = 0, changed = 0;
  const Eigen::Isometry3d T_L_W = T_W_L.inverse();
  for (const auto& [b, block] : obs.tsdf.blocks()) {
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      const TsdfVoxel& v = block[static_cast<std::size_t>(i)];
      if (v.weight <= 0.0f) continue;
      ++kept;
      const GlobalVoxelIndex idx_O = b * kBlockEdge + Eigen::Vector3i(i % 8, i / 8 % 8, i / 64);
      const Eigen::Vector3d p_W = voxelCenter(idx_O + offset, kVoxel).cast<double>();
      if (test::boxSdf(T_L_W * p_W, kBox) > band_m + kVoxel) ++far_from_box;
      const TsdfVoxel* w = s.map.findVoxel(idx_O + offset);
      if (w == nullptr || w->tsdf_m != v.tsdf_m || w->weight != v.weight ||
          w->color_rgba != v.color_rgba) {
        ++changed;
      }
    }
  }
  EXPECT_GT(kept, 5000u);
  EXPECT_EQ(far_from_box, 0u);
  EXPECT_EQ(changed, 0u);
  const Eigen::Vector3d floor_W(0.3, 0.3, 0.01);
  const TsdfVoxel* floor =
      obs.tsdf.findVoxel((floor_W / kVoxel).array().floor().cast<int>().matrix() - offset);
  EXPECT_TRUE(floor == nullptr || floor->weight == 0.0f);

  // The zero crossing at the centre of the top and of each side.
  const Eigen::Vector3d faces_L[] = {
      {0, 0, 0.4}, {0.2, 0, 0.2}, {-0.2, 0, 0.2}, {0, 0.15, 0.2}, {0, -0.15, 0.2}};
  for (const auto& f_L : faces_L) {
    const auto d = sampleTsdf(obs.tsdf, (T_W_L * f_L - t).cast<float>(), 1e-3f);
    ASSERT_TRUE(d.has_value()) << f_L.transpose();
    EXPECT_NEAR(d->distance_m, 0.0f, 0.5f * kVoxel) << f_L.transpose();
  }

  const Mesh mesh = extractMesh(obs.tsdf);
  const double area = meshArea(mesh);
  std::cout << "observation: " << kept << " voxels, mesh area " << area << " m^2 (box "
            << kBoxVisibleAreaM2 << "), " << obs.surface_O.size() << " samples\n";
  EXPECT_NEAR(area, kBoxVisibleAreaM2, 0.15 * kBoxVisibleAreaM2);
  EXPECT_NEAR(obs.surface_area_m2, kBoxVisibleAreaM2, 0.2 * kBoxVisibleAreaM2);

  // Descriptors: extent sorted descending (0.4, 0.4, 0.3 plus floor fringe), grey, unit normals.
  EXPECT_GE(obs.extent_m[0], obs.extent_m[1]);
  EXPECT_GE(obs.extent_m[1], obs.extent_m[2]);
  EXPECT_NEAR(obs.extent_m[0], 0.4f, 0.07f);
  EXPECT_NEAR(obs.extent_m[2], 0.3f, 0.07f);
  EXPECT_NEAR(obs.mean_color.x(), 128.0f, 1.0f);
  ASSERT_EQ(obs.surface_O.normals.size(), obs.surface_O.size());
  for (const auto& n : obs.surface_O.normals) EXPECT_NEAR(n.norm(), 1.0f, 1e-4f);
}

TEST(ObjectVolume, DegenerateSegmentsAreRefusedWithTheReason) {
  const test::ObjectSession s =
      test::makeObjectSession(boxAt(test::floorPose(0.8, 0.75, 0.0)), kEverywhere, 1);
  ASSERT_EQ(s.objects.size(), 1u);
  const auto expectRefused = [&](const Mesh& mesh, const std::string& reason) {
    change::DiscoveredObject segment = s.objects[0];
    segment.mesh = mesh;
    try {
      observeObject(s.map, s.surface, segment, 1);
      ADD_FAILURE() << "not refused: " << reason;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
    }
  };
  // The top alone: a plane with plenty of samples.
  expectRefused(subMesh(s.objects[0].mesh, [](const Eigen::Vector3f& p) { return p.z() > 0.39f; }),
                "planar");
  // A few centimetres of the top: too few samples.
  const Eigen::Vector3f top_centre(0.8f, 0.75f, 0.4f);
  expectRefused(subMesh(s.objects[0].mesh,
                        [&](const Eigen::Vector3f& p) { return (p - top_centre).norm() < 0.05f; }),
                "too few surface samples");

  ObservationConfig bad;
  bad.band_voxels = 0.0f;
  try {
    observeObject(s.map, s.surface, s.objects[0], 1, bad);
    ADD_FAILURE() << "band_voxels = 0 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("band_voxels"), std::string::npos) << e.what();
  }
  EXPECT_THROW(sampleSurface(s.objects[0].mesh, 0.0f), InputError);
}

TEST(ObjectVolume, SampleSurfaceThinsDeterministicallyAndMakesNormals) {
  const test::ObjectSession s =
      test::makeObjectSession(boxAt(test::floorPose(0.8, 0.75, 0.0)), kEverywhere, 1);
  ASSERT_EQ(s.objects.size(), 1u);
  Mesh mesh = s.objects[0].mesh;
  const SurfaceCloud a = sampleSurface(mesh, 2 * kVoxel);
  const SurfaceCloud b = sampleSurface(mesh, 2 * kVoxel);
  EXPECT_EQ(a.points, b.points);
  // One sample per occupied cube at most: no two samples share a cube.
  std::map<std::tuple<int, int, int>, int> cubes;
  for (const auto& p : a.points) {
    const Eigen::Vector3i c = (p / (2 * kVoxel)).array().floor().cast<int>();
    EXPECT_EQ(++cubes[std::make_tuple(c.x(), c.y(), c.z())], 1);
  }
  EXPECT_LT(a.size(), mesh.vertices.size() / 2);
  // Without mesh normals the faces give them: on the top they point up.
  mesh.normals.clear();
  const SurfaceCloud c = sampleSurface(mesh, 2 * kVoxel);
  ASSERT_EQ(c.normals.size(), c.size());
  std::size_t top = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (c.points[i].z() > 0.39f && std::abs(c.points[i].x() - 0.8f) < 0.15f &&
        std::abs(c.points[i].y() - 0.75f) < 0.1f) {
      ++top;
      EXPECT_GT(c.normals[i].z(), 0.99f);
    }
  }
  EXPECT_GT(top, 20u);
}

TEST(ObjectVolume, SampleTsdfIsExactOnALinearField) {
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, -0.5, 0.81).normalized();
  const auto plane = [n](const Eigen::Vector3d& p) { return n.dot(p) - 0.2; };
  const auto observed = [](const Eigen::Vector3d& p) { return p.x() < 0.4; };
  const TsdfMap map = test::makeSdfMap(plane, {0, 0, 0}, {0.6, 0.6, 0.6}, kVoxel, observed);
  std::size_t checked = 0;
  for (int i = 0; i < 400; ++i) {
    // A deterministic spread of points within a voxel of the plane.
    const Eigen::Vector3d q(0.05 + 0.3 * std::fmod(i * 0.618034, 1.0),
                            0.05 + 0.5 * std::fmod(i * 0.414214, 1.0), 0.0);
    const double offset = kVoxel * (std::fmod(i * 0.732051, 2.0) - 1.0);
    const Eigen::Vector3d p = q + n * (offset - plane(q));
    if ((p.array() < 0.03).any() || (p.array() > 0.58).any() || p.x() > 0.36) continue;
    const auto s = sampleTsdf(map, p.cast<float>(), 1e-3f);
    ASSERT_TRUE(s.has_value()) << p.transpose();
    EXPECT_NEAR(s->distance_m, plane(p), 1e-5) << p.transpose();
    EXPECT_EQ(s->weight, 20.0f);
    EXPECT_NEAR(s->color.x(), 128.0f, 1e-3f);
    ++checked;
  }
  EXPECT_GT(checked, 200u);
  // Where a corner is unobserved there is no sample.
  EXPECT_FALSE(sampleTsdf(map, Eigen::Vector3f(0.5f, 0.3f, 0.3f), 1e-3f).has_value());
  EXPECT_FALSE(sampleTsdf(map, Eigen::Vector3f(0.40f, 0.3f, 0.3f), 1e-3f).has_value());
  // At a voxel centre the sample is that voxel, even at the edge of the observed part.
  const GlobalVoxelIndex last(19, 10, 10);  // x centre 0.39, its +x neighbour unobserved
  const auto at = sampleTsdf(map, voxelCenter(last, kVoxel), 1e-3f);
  ASSERT_TRUE(at.has_value());
  EXPECT_EQ(at->distance_m, map.findVoxel(last)->tsdf_m);
}

/// Session 1 sees the box (no yaw) only where world x < its centre; session 2 sees it elsewhere,
/// yawed by 30 degrees, only on its own +x half.
struct TwoHalves {
  Eigen::Isometry3d T_W1_L = test::floorPose(0.7, 0.8, 0.0);
  Eigen::Isometry3d T_W2_L = test::floorPose(0.85, 0.7, kPi / 6.0);
  ObjectObservation first, second;
  TwoHalves() {
    const auto half1 = [](const Eigen::Vector3d& p) { return p.x() < 0.7; };
    const Eigen::Isometry3d T_L_W2 = T_W2_L.inverse();
    const auto half2 = [T_L_W2](const Eigen::Vector3d& p) { return (T_L_W2 * p).x() > 0.0; };
    first = observeOnly(test::makeObjectSession(boxAt(T_W1_L), half1, 1), 1);
    second = observeOnly(test::makeObjectSession(boxAt(T_W2_L), half2, 2), 2);
  }
  /// The true pose of the second observation in the first's frame (= the model's).
  Eigen::Isometry3d T_M_O2() const {
    return first.T_W_O.inverse() * T_W1_L * T_W2_L.inverse() * second.T_W_O;
  }
  Eigen::Isometry3d T_L_M() const { return T_W1_L.inverse() * first.T_W_O; }
};

TEST(ObjectVolume, MergingTwoHalvesCoversTheBox) {
  const TwoHalves views;
  const ObjectModelConfig config;
  ObjectModel model = foundModel(1, views.first, config);
  const ObjectModel alone = foundModel(2, views.second, config);
  ASSERT_EQ(model.instances.size(), 1u);
  EXPECT_EQ(model.instances[0].session, 1);
  EXPECT_TRUE(model.instances[0].T_W_M.isApprox(views.first.T_W_O));
  const double area_first = model.surface_area_m2, area_second = alone.surface_area_m2;

  mergeObservation(model, views.second, views.T_M_O2(), config);
  refreshModel(model, kVoxel, config);
  EXPECT_EQ(model.instances.size(), 1u);  // the database adds instances, not the merge
  const double ratio = model.surface_area_m2 / std::max(area_first, area_second);
  const double mean_m = meanSceneDistance(model.mesh_M, views.T_L_M());
  std::cout << "halves: " << area_first << " and " << area_second << " m^2, merged "
            << model.surface_area_m2 << " m^2 (x" << ratio << ", box " << kBoxVisibleAreaM2
            << "), mean distance to the true surface " << mean_m * 1000.0 << " mm\n";
  EXPECT_GE(ratio, 1.5);
  EXPECT_LT(model.surface_area_m2, 1.25 * kBoxVisibleAreaM2);  // little floor came along
  EXPECT_LT(mean_m, 0.5 * kVoxel);
  // Placed wrongly (a 5 cm shift) the merge leaves a visibly worse surface.
  ObjectModel shifted = foundModel(1, views.first, config);
  mergeObservation(shifted, views.second, Eigen::Translation3d(0.05, 0.0, 0.0) * views.T_M_O2(),
                   config);
  refreshModel(shifted, kVoxel, config);
  EXPECT_GT(meanSceneDistance(shifted.mesh_M, views.T_L_M()), mean_m + 0.25 * kVoxel);
  // Extent and surface samples follow the merged shape.
  EXPECT_NEAR(model.extent_m[0], 0.4f, 0.07f);
  EXPECT_NEAR(model.extent_m[2], 0.3f, 0.07f);
  EXPECT_GT(model.surface_M.size(), alone.surface_M.size());
}

TEST(ObjectVolume, MergingTheSameObservationTwiceDoublesTheWeights) {
  const test::ObjectSession s =
      test::makeObjectSession(boxAt(test::floorPose(0.8, 0.75, 0.0)), kEverywhere, 1);
  const ObjectObservation obs = observeOnly(s, 1);
  const ObjectModelConfig config;
  ObjectModel model = foundModel(1, obs, config);
  const TsdfMap before = model.tsdf;
  mergeObservation(model, obs, Eigen::Isometry3d::Identity(), config);
  std::size_t observed = 0, moved = 0, not_doubled = 0, new_voxels = 0;
  for (const auto& [b, block] : model.tsdf.blocks()) {
    const TsdfBlock* old = before.findBlock(b);
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      const TsdfVoxel& v = block[static_cast<std::size_t>(i)];
      const TsdfVoxel* o = old ? &(*old)[static_cast<std::size_t>(i)] : nullptr;
      if (o == nullptr || o->weight == 0.0f) {
        new_voxels += v.weight > 0.0f ? 1 : 0;
        continue;
      }
      ++observed;
      if (std::abs(v.tsdf_m - o->tsdf_m) > 1e-6f) ++moved;
      if (v.weight != 2.0f * o->weight) ++not_doubled;
    }
  }
  EXPECT_GT(observed, 5000u);
  EXPECT_EQ(moved, 0u);
  EXPECT_EQ(not_doubled, 0u);
  EXPECT_EQ(new_voxels, 0u);
  // The weight is capped.
  ObjectModelConfig low = config;
  low.max_weight = 30.0f;
  ObjectModel capped = foundModel(1, obs, low);
  mergeObservation(capped, obs, Eigen::Isometry3d::Identity(), low);
  for (const auto& [b, block] : capped.tsdf.blocks()) {
    for (const TsdfVoxel& v : block) EXPECT_LE(v.weight, 30.0f);
  }
}

TEST(ObjectVolume, AFinerModelGridResamplesTheObservation) {
  const Eigen::Isometry3d T_W_L = test::floorPose(0.8, 0.75, 0.0);
  const test::ObjectSession s = test::makeObjectSession(boxAt(T_W_L), kEverywhere, 1);
  const ObjectObservation obs = observeOnly(s, 1);
  ObjectModelConfig fine;
  fine.voxel_size_m = 0.5f * kVoxel;
  const ObjectModel model = foundModel(1, obs, fine);
  const ObjectModel coarse = foundModel(2, obs, ObjectModelConfig{});
  EXPECT_FLOAT_EQ(model.tsdf.config().voxel_size_m, 0.5f * kVoxel);
  EXPECT_FLOAT_EQ(model.tsdf.config().truncationDistance(), obs.tsdf.config().truncationDistance());
  EXPECT_NEAR(model.surface_area_m2, coarse.surface_area_m2, 0.1 * coarse.surface_area_m2);
  EXPECT_LT(meanSceneDistance(model.mesh_M, T_W_L.inverse() * obs.T_W_O), 0.5 * kVoxel);
  ObjectModelConfig bad;
  bad.min_weight = -1.0f;
  EXPECT_THROW(foundModel(1, obs, bad), InputError);
}

}  // namespace
}  // namespace strata::objects
