// The Mapper end to end: fuse, ESDF query, mesh, save, load (identical bytes) on the analytic
// scene (against its exact geometry and the C++ reference fusion) and on the real redkitchen
// frames; a session round trip with change detection (one fusion pass, the same result as the
// ChangeDetector driven directly); bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "strata/change/change_detector.h"
#include "change_pipeline_helpers.h"
#include "strata/core/error.h"
#include "strata/mapper/eval/accuracy.h"
#include "fusion_fixture.h"
#include "strata/io/open_dataset.h"
#include "strata/map/map_file.h"
#include "map_compare.h"
#include "strata/mapper/mapper.h"
#include "strata/mesh/extract_mesh.h"
#include "strata/sim/analytic_dataset.h"
#include "test_utils.h"

namespace strata {
namespace {

std::vector<std::uint8_t> fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("strata_test_mapper_" + name)).string();
}

/// A Mapper with change detection on the test grid (free space allocated) at `voxel_m`.
MapperConfig changeConfig(float voxel_m) {
  MapperConfig config;
  config.map = test::testMapConfig(voxel_m, true);
  config.change_detection = true;
  config.change = test::testChangeConfig(voxel_m);
  return config;
}

/// save -> load -> save gives the same bytes, and the loaded mapper meshes the same surface.
void expectRoundTrip(Mapper& mapper, const MapperConfig& config, const std::string& name) {
  const std::string first = tempPath(name + "_1.strata");
  const std::string second = tempPath(name + "_2.strata");
  mapper.save(first);
  const std::unique_ptr<Mapper> loaded = Mapper::load(first, test::sharedContext(), config);
  loaded->save(second);
  const std::vector<std::uint8_t> a = fileBytes(first);
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, fileBytes(second)) << "save -> load -> save must give identical bytes";
  EXPECT_EQ(loaded->mesh().triangles.size(), mapper.mesh().triangles.size());
  std::remove(first.c_str());
  std::remove(second.c_str());
}

TEST(Mapper, AnalyticSceneFusesLikeTheReferenceAndMatchesTheExactScene) {
  const sim::AnalyticDataset data;
  MapperConfig config;
  config.map.voxel_size_m = 0.04f;
  config.map.allocate_free_space = true;
  config.esdf = true;
  Mapper mapper(config, test::sharedContext());
  const std::size_t frames = 8;
  for (std::size_t i = 0; i < frames; ++i) {
    const IntegrateStats stats = mapper.integrate(data.load(i), data.intrinsics());
    EXPECT_GT(stats.fusion.touched_blocks, 0u);
    EXPECT_EQ(stats.blocks, mapper.blockCount());
  }
  EXPECT_EQ(mapper.framesIntegrated(), frames);

  // Device fusion through the facade equals the C++ reference of the same frames.
  const TsdfMap map = mapper.download();
  const TsdfMap reference = test::fuseReference(data, config.map, frames);
  const test::MapDifference diff = test::compareMaps(map, reference, 1e-4f, 1e-4f);
  EXPECT_EQ(diff.blocks_only_in_a + diff.blocks_only_in_b, 0u);
  EXPECT_LT(diff.distanceMismatchShare(), 1e-3);

  // ... and both agree with the exact scene.
  const Mesh mesh = mapper.mesh();
  ASSERT_FALSE(mesh.empty());
  const auto accuracy = eval::evaluateMesh(mesh, data.scene(), 0.5f * config.map.voxel_size_m);
  EXPECT_GT(accuracy.fraction_within, 0.95);

  // ESDF queries: the exact signed distance of the scene within a voxel where known.
  const EsdfUpdateStats esdf = mapper.updateEsdf();
  EXPECT_TRUE(esdf.full) << "the first update is a full one";
  std::size_t known = 0, close = 0;
  for (const Eigen::Vector3f& v : mesh.vertices) {
    const Eigen::Vector3f n = Eigen::Vector3f::UnitZ();
    const Eigen::Vector3f p = v + 0.2f * n;  // 20 cm above a surface point
    const EsdfSample s = mapper.distance(p);
    if (s.status != EsdfStatus::kKnown) continue;
    ++known;
    const double truth = data.scene().signedDistance(Eigen::Vector3d(p.cast<double>()));
    close += std::abs(s.distance_m - truth) <= config.map.voxel_size_m ? 1 : 0;
    if (known == 500) break;
  }
  ASSERT_GT(known, 100u);
  EXPECT_GT(static_cast<double>(close) / known, 0.9);
  // Collision checks: a point on the surface is not free; a second update is incremental.
  EXPECT_FALSE(mapper.isSphereFree(mesh.vertices.front(), 0.05f));
  mapper.integrate(data.load(frames), data.intrinsics());
  EXPECT_FALSE(mapper.updateEsdf().full);

  expectRoundTrip(mapper, config, "analytic");
}

TEST(Mapper, StreamsChangedBlocksWhoseUnionIsTheMesh) {
  const sim::AnalyticDataset data;
  MapperConfig config;
  config.map.voxel_size_m = 0.05f;
  Mapper mapper(config, test::sharedContext());
  mapper.integrate(data.load(0), data.intrinsics());
  MeshOptions options;
  options.compute_normals = false;
  std::size_t first = 0;
  for (const BlockMesh& b : mapper.meshChangedBlocks(options)) first += b.mesh.triangles.size();
  EXPECT_EQ(first, mapper.mesh(options).triangles.size()) << "the first call sends everything";
  EXPECT_TRUE(mapper.meshChangedBlocks(options).empty()) << "nothing fused since";
  mapper.integrate(data.load(3), data.intrinsics());
  EXPECT_FALSE(mapper.meshChangedBlocks(options).empty());
}

TEST(Mapper, RealKitchenFramesFuseQueryMeshAndRoundTrip) {
  STRATA_REQUIRE_DATA("redkitchen", folder);
  const std::unique_ptr<Dataset> data = openDataset(folder, {});
  MapperConfig config;
  config.map.voxel_size_m = 0.04f;
  config.esdf = true;
  config.keyframe_scoring = true;
  Mapper mapper(config, test::sharedContext());
  for (std::size_t i = 0; i < 30; i += 3) {
    const RgbdFrame frame = data->load(i);
    const KeyframeDecision decision = mapper.scoreKeyframe(frame, data->intrinsics());
    if (i == 0) {
      EXPECT_TRUE(decision.keyframe) << "an empty map explains nothing";
    }
    mapper.integrate(frame, data->intrinsics());
  }
  // The next frame of the same view: the map covers most of it.
  const KeyframeDecision next = mapper.scoreKeyframe(data->load(31), data->intrinsics());
  EXPECT_GT(next.score.coverage, 0.5);

  const Mesh mesh = mapper.mesh();
  EXPECT_GT(mesh.triangles.size(), 5000u);  // 10 frames at 4 cm: about 8k
  mapper.updateEsdf();
  // Surface vertices are within a voxel or two of an obstacle.
  std::size_t near = 0, known = 0;
  for (std::size_t i = 0; i < mesh.vertices.size(); i += 97) {
    const EsdfSample s = mapper.distance(mesh.vertices[i]);
    if (s.status != EsdfStatus::kKnown) continue;
    ++known;
    near += std::abs(s.distance_m) <= 2.0f * config.map.voxel_size_m ? 1 : 0;
  }
  ASSERT_GT(known, 50u);
  EXPECT_GT(static_cast<double>(near) / known, 0.9);
  // A rendering from the last pose hits the map over most of the image.
  const RaycastImage image = mapper.render(data->intrinsics(), data->load(27).T_W_C);
  std::size_t hits = 0;
  for (std::uint8_t h : image.hit) hits += h;
  EXPECT_GT(static_cast<double>(hits) / image.hit.size(), 0.5);

  expectRoundTrip(mapper, config, "kitchen");
}

/// The box that appears between the two analytic sessions of the session tests.
sim::Box appearingBox() {
  sim::Box box;
  box.centre_W = Eigen::Vector3d(-1.0, -0.3, 0.15);
  box.half_extents_m = Eigen::Vector3d(0.15, 0.15, 0.15);
  return box;
}

TEST(Mapper, SessionRoundTripFusesOnceAndFindsWhatTheDetectorFinds) {
  const sim::Box box = appearingBox();
  const sim::AnalyticDataset before = test::analyticSession({}, 6);
  const sim::AnalyticDataset after = test::analyticSession({box}, 6);
  const float voxel_m = 0.04f;

  MapperConfig config = changeConfig(voxel_m);
  Mapper mapper(config, test::sharedContext());
  EXPECT_EQ(mapper.beginSession(), 0);
  for (std::size_t i = 0; i < before.size(); ++i) mapper.integrate(before.load(i), before.intrinsics());
  EXPECT_EQ(mapper.liveLayer(), 1) << "session 0 fuses into its own layer";
  const SessionResult first = mapper.endSession();
  EXPECT_EQ(first.frames, before.size());
  EXPECT_EQ(mapper.beginSession(), 1);
  for (std::size_t i = 0; i < after.size(); ++i) mapper.integrate(after.load(i), after.intrinsics());
  const TsdfMap session_layer = mapper.download();
  const SessionResult second = mapper.endSession();

  // The same sessions through the ChangeDetector directly.
  change::ChangeDetector detector(test::sharedContext(), config.map, config.change);
  for (const sim::AnalyticDataset* data : {&before, &after}) {
    const int s = detector.beginSession();
    test::fuseSession(detector, s, *data, data->size());
    detector.endSession(s);
  }
  EXPECT_EQ(test::compareValues(session_layer, detector.sessionMap(1), 0.0f, 1e-6f).over_tolerance,
            0u) << "one fusion pass into the session layer, as the detector's own";
  EXPECT_EQ(test::compareValues(mapper.staticMap(), detector.staticMap(), 0.0f, 1e-6f)
                .over_tolerance, 0u);
  const auto direct = change::sessionObjects(detector, 1, config.objects);
  ASSERT_EQ(second.objects.size(), direct.size());
  ASSERT_GE(second.objects.size(), 1u) << "the box that appeared";
  const Eigen::AlignedBox3f truth((box.centre_W - box.half_extents_m).cast<float>(),
                                  (box.centre_W + box.half_extents_m).cast<float>());
  EXPECT_TRUE(truth.contains(second.objects.front().centroid));
  EXPECT_TRUE(first.objects.empty()) << "the first session has nothing to differ from";
}

/// Ends `count` sessions alternating `before` and `after`; the objects each ended session found.
std::vector<SessionResult> runSessions(Mapper& mapper, const sim::AnalyticDataset& before,
                                       const sim::AnalyticDataset& after, int count,
                                       std::vector<std::uint64_t>* device_bytes = nullptr) {
  std::vector<SessionResult> results;
  for (int s = 0; s < count; ++s) {
    const sim::AnalyticDataset& data = s % 2 == 0 ? before : after;
    mapper.beginSession();
    for (std::size_t i = 0; i < data.size(); ++i) mapper.integrate(data.load(i), data.intrinsics());
    results.push_back(mapper.endSession());
    if (device_bytes) device_bytes->push_back(test::sharedContext().allocatedBytes());
  }
  return results;
}

TEST(Mapper, ReleasedSessionsKeepDeviceMemoryFlatAndFindTheSameObjects) {
  const sim::AnalyticDataset before = test::analyticSession({}, 6);
  const sim::AnalyticDataset after = test::analyticSession({appearingBox()}, 6);
  const float voxel_m = 0.04f;
  MapperConfig config = changeConfig(voxel_m);

  std::vector<SessionResult> kept_results;
  {
    Mapper keeping(config, test::sharedContext());
    kept_results = runSessions(keeping, before, after, 4);
  }
  config.release_ended_sessions = true;
  config.keep_session_evidence = true;  // taken before the layers are released
  Mapper releasing(config, test::sharedContext());
  std::vector<std::uint64_t> device_bytes;
  const std::vector<SessionResult> results =
      runSessions(releasing, before, after, 4, &device_bytes);

  // Sessions 2 and 3 reuse the layers sessions 0 and 1 released: no new device memory (a leak of
  // two layers per session, 64 MiB at 2 cm, was what the soak found before release existed).
  for (std::size_t s = 2; s < device_bytes.size(); ++s) {
    EXPECT_EQ(device_bytes[s], device_bytes[1]) << "device bytes after session " << s;
  }
  ASSERT_EQ(results.size(), kept_results.size());
  for (std::size_t s = 0; s < results.size(); ++s) {
    ASSERT_EQ(results[s].objects.size(), kept_results[s].objects.size()) << "session " << s;
    for (std::size_t o = 0; o < results[s].objects.size(); ++o) {
      EXPECT_LT((results[s].objects[o].centroid - kept_results[s].objects[o].centroid).norm(), 1e-5f)
          << "session " << s << " object " << o << ": a reused layer starts clean";
    }
  }
  EXPECT_FALSE(results[1].objects.empty()) << "the box appears in every odd session";
  EXPECT_THROW(releasing.changeDetector().sessionMap(0), InputError) << "released";
  // The evidence the object database needs: the session's map and its labelled surface.
  EXPECT_FALSE(kept_results[1].session_map.has_value()) << "only kept when asked for";
  for (std::size_t s = 0; s < results.size(); ++s) {
    ASSERT_TRUE(results[s].session_map.has_value()) << "session " << s;
    EXPECT_GT(results[s].session_map->blockCount(), 0u) << "session " << s;
    const change::LabelledSurface& surface = results[s].surface;
    EXPECT_FALSE(surface.mesh.empty()) << "session " << s;
    ASSERT_EQ(surface.face_dynamic.size(), surface.mesh.triangles.size()) << "session " << s;
    const auto dynamic_faces =
        std::count(surface.face_dynamic.begin(), surface.face_dynamic.end(), true);
    if (results[s].objects.empty()) continue;
    std::size_t object_faces = 0;
    for (const change::DiscoveredObject& o : results[s].objects) {
      object_faces += o.mesh.triangles.size();
    }
    EXPECT_GE(static_cast<std::size_t>(dynamic_faces), object_faces)
        << "session " << s << ": every object face is a dynamic face of the surface";
  }
}

TEST(Mapper, ASavedMapAsASessionFindsWhatFusingTheSessionFinds) {
  const sim::Box box = appearingBox();
  const sim::AnalyticDataset before = test::analyticSession({}, 6);
  const sim::AnalyticDataset after = test::analyticSession({box}, 6);
  const float voxel_m = 0.04f;
  MapperConfig plain;
  plain.map = test::testMapConfig(voxel_m, true);
  Mapper other_day(plain, test::sharedContext());
  for (std::size_t i = 0; i < after.size(); ++i) other_day.integrate(after.load(i), after.intrinsics());
  const TsdfMap saved = other_day.download();

  MapperConfig config = plain;
  config.change_detection = true;
  config.change = test::testChangeConfig(voxel_m);
  Mapper mapper(config, test::sharedContext());
  mapper.beginSession();
  for (std::size_t i = 0; i < before.size(); ++i) mapper.integrate(before.load(i), before.intrinsics());
  EXPECT_THROW(mapper.addSessionMap(saved), InputError) << "a session is open";
  mapper.endSession();
  const SessionResult added = mapper.addSessionMap(saved);
  EXPECT_EQ(added.session, 1);
  EXPECT_EQ(mapper.sessionCount(), 2);
  ASSERT_GE(added.objects.size(), 1u) << "the box the saved map holds";
  const Eigen::AlignedBox3f truth((box.centre_W - box.half_extents_m).cast<float>(),
                                  (box.centre_W + box.half_extents_m).cast<float>());
  EXPECT_TRUE(truth.contains(added.objects.front().centroid));

  MapperConfig quiet = config;
  quiet.discover_objects = false;  // discovered later against the final static map
  Mapper later(quiet, test::sharedContext());
  later.beginSession();
  for (std::size_t i = 0; i < before.size(); ++i) later.integrate(before.load(i), before.intrinsics());
  later.endSession();
  EXPECT_TRUE(later.addSessionMap(saved).objects.empty()) << "the box is there, not discovered";
  EXPECT_FALSE(change::sessionObjects(later.changeDetector(), 1, config.objects).empty());
  EXPECT_THROW(other_day.addSessionMap(saved), InputError) << "change detection off";
  EXPECT_THROW(other_day.changeDetector(), InputError);
}

/// runSessions with a kill and a restart before frame `cut_frame` of session `cut_session` (-1:
/// before the session begins): the state a mapper saves, in bytes, is all that survives.
std::vector<SessionResult> runSessionsWithRestart(const MapperConfig& config,
                                                  const sim::AnalyticDataset& before,
                                                  const sim::AnalyticDataset& after, int count,
                                                  int cut_session, int cut_frame,
                                                  TsdfMap* static_map) {
  auto mapper = std::make_unique<Mapper>(config, test::sharedContext());
  auto restart = [&](int session) {
    const std::vector<std::uint8_t> bytes = serializeMapFile(mapper->snapshot());
    const bool was_open = mapper->sessionOpen();
    mapper.reset();  // the kill: nothing but the bytes survives
    mapper = Mapper::resume(deserializeMapFile(bytes, "state"), test::sharedContext(), config);
    EXPECT_EQ(mapper->sessionOpen(), was_open);
    EXPECT_EQ(mapper->sessionCount(), session + (was_open ? 1 : 0));
  };
  std::vector<SessionResult> results;
  for (int s = 0; s < count; ++s) {
    const sim::AnalyticDataset& data = s % 2 == 0 ? before : after;
    if (s == cut_session && cut_frame < 0) restart(s);
    mapper->beginSession();
    for (std::size_t i = 0; i < data.size(); ++i) {
      if (s == cut_session && static_cast<int>(i) == cut_frame) restart(s);
      mapper->integrate(data.load(i), data.intrinsics());
    }
    results.push_back(mapper->endSession());
  }
  *static_map = mapper->staticMap();
  return results;
}

TEST(Mapper, ResumedFromASavedStateEndsAsTheMapperThatWentOn) {
  const sim::AnalyticDataset before = test::analyticSession({}, 6);
  const sim::AnalyticDataset after = test::analyticSession({appearingBox()}, 6);
  const float voxel_m = 0.04f;
  MapperConfig config = changeConfig(voxel_m);
  config.release_ended_sessions = true;  // as strata-mapper runs
  TsdfMap whole_static(config.map);
  const std::vector<SessionResult> whole =
      runSessionsWithRestart(config, before, after, 3, -1, 0, &whole_static);
  ASSERT_FALSE(whole[1].objects.empty()) << "the box appears in session 1";

  // In the first session (S still empty), in the second (S holds session 0) and between them.
  for (const auto& [session, frame] : {std::pair{0, 3}, std::pair{1, 2}, std::pair{1, -1}}) {
    SCOPED_TRACE("restart before frame " + std::to_string(frame) + " of session " +
                 std::to_string(session));
    TsdfMap resumed_static(config.map);
    const std::vector<SessionResult> resumed =
        runSessionsWithRestart(config, before, after, 3, session, frame, &resumed_static);
    const test::MapDifference diff = test::compareMaps(whole_static, resumed_static, 0.0f, 0.0f);
    EXPECT_GT(diff.updated_voxels, 1000u);
    EXPECT_EQ(diff.blocks_only_in_a + diff.blocks_only_in_b, 0u);
    EXPECT_EQ(diff.distance_mismatches, 0u) << "max " << diff.max_distance_difference_m << " m";
    EXPECT_EQ(diff.weight_mismatches, 0u);
    EXPECT_EQ(diff.color_mismatches, 0u);
    ASSERT_EQ(resumed.size(), whole.size());
    for (std::size_t s = 0; s < whole.size(); ++s) {
      EXPECT_EQ(resumed[s].session, whole[s].session);
      ASSERT_EQ(resumed[s].objects.size(), whole[s].objects.size()) << "session " << s;
      for (std::size_t o = 0; o < whole[s].objects.size(); ++o) {
        EXPECT_EQ(resumed[s].objects[o].centroid, whole[s].objects[o].centroid);
      }
    }
  }
}

TEST(Mapper, AnOpenChangeSessionDoesNotResumeWithoutChangeDetection) {
  const sim::AnalyticDataset data = test::analyticSession({}, 2);
  const MapperConfig config = changeConfig(0.04f);
  Mapper mapper(config, test::sharedContext());
  mapper.integrate(data.load(0), data.intrinsics());
  const MapFileContents open = mapper.snapshot();
  ASSERT_TRUE(open.sessions.has_value());
  EXPECT_TRUE(open.sessions->session_open);
  MapperConfig plain;
  plain.map = config.map;
  try {
    Mapper::resume(open, test::sharedContext(), plain);
    FAIL() << "an open session's layer became a plain map";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("change detection on"), std::string::npos) << e.what();
  }
  mapper.endSession();
  const std::unique_ptr<Mapper> plain_mapper =
      Mapper::resume(mapper.snapshot(), test::sharedContext(), plain);
  EXPECT_EQ(plain_mapper->blockCount(), mapper.blockCount()) << "an ended state is its S";
}

TEST(Mapper, BadInputIsRefusedBeforeAnythingChanges) {
  MapperConfig bad;
  bad.map.voxel_size_m = -1.0f;
  EXPECT_THROW(Mapper(bad, test::sharedContext()), InputError);
  MapperConfig config;
  config.map.voxel_size_m = 0.05f;
  Mapper mapper(config, test::sharedContext());
  const sim::AnalyticDataset data;
  EXPECT_THROW(mapper.updateEsdf(), InputError) << "ESDF off";
  EXPECT_THROW(mapper.scoreKeyframe(data.load(0), data.intrinsics()), InputError) << "scoring off";
  EXPECT_THROW(mapper.endSession(), InputError) << "no session open";
  Eigen::Isometry3d nan_pose = Eigen::Isometry3d::Identity();
  nan_pose.translation().x() = std::nan("");
  EXPECT_THROW(mapper.integrate(data.load(0), data.intrinsics(), nan_pose), InputError);
  EXPECT_EQ(mapper.blockCount(), 0u);
  EXPECT_THROW(Mapper::load(tempPath("missing.strata"), test::sharedContext()), Error);
}

}  // namespace
}  // namespace strata
