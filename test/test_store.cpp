// The session store: every table round-trips, transactions roll back on exceptions, schema
// versions are checked, damaged files and failed writes are refused with clear messages, and
// changed resources are detected.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/store/schema.h"
#include "strata/store/session_store.h"
#include "store_test_helpers.h"

namespace strata::test {
namespace {

namespace fs = std::filesystem;
using store::EdgeKind;
using store::EdgeRecord;
using store::KeyframeRecord;
using store::Store;

std::vector<KeyframeRecord> someKeyframes(std::int64_t session_id, int n) {
  std::vector<KeyframeRecord> out;
  for (int i = 0; i < n; ++i) {
    KeyframeRecord k;
    k.session_id = session_id;
    k.timestamp_s = 100.0 + 0.5 * i;
    k.T_S_C = samplePose(i);
    out.push_back(k);
  }
  return out;
}

template <typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Store, EveryTableRoundTrips) {
  const fs::path dir = freshStoreDir("round_trip");
  const fs::path db_path = dir / "map.sqlite";
  std::vector<std::int64_t> ids;
  store::Matrix6d covariance = store::Matrix6d::Identity() * 1e-4;
  covariance(0, 3) = covariance(3, 0) = 2e-5;
  store::Matrix6d information = store::Matrix6d::Identity() * 250.0;
  information(1, 4) = information(4, 1) = -3.5;
  store::FeatureSet features;
  features.format = "orb";
  features.descriptor_bytes = 32;
  for (int i = 0; i < 5; ++i) features.keypoints_px.emplace_back(10.5f * i, 480.0f - i);
  for (int i = 0; i < 5 * 32; ++i) features.descriptors.push_back(static_cast<std::uint8_t>(i * 7));
  const fs::path image = dir / "depth_0.png";
  writeRandomFile(image, 1000, 1);
  {
    Store store(db_path.string());
    const std::int64_t a = store.addSession("mission_a", (dir / "a").string());
    const std::int64_t b = store.addSession("mission_b", (dir / "b").string());
    auto keyframes = someKeyframes(a, 3);
    keyframes[1].covariance = covariance;
    keyframes[2].T_W_C = samplePose(7);
    // Handed in out of time order: queries return time order.
    std::swap(keyframes[0], keyframes[2]);
    ids = store.addKeyframes(keyframes);
    const auto b_ids = store.addKeyframes(someKeyframes(b, 2));
    std::vector<EdgeRecord> edges(3);
    edges[0].from_keyframe = ids[0];
    edges[0].to_keyframe = ids[1];
    edges[0].T_from_to = samplePose(3);
    edges[0].information = information;
    edges[1].kind = EdgeKind::kLoop;
    edges[1].from_keyframe = ids[1];
    edges[1].to_keyframe = b_ids[1];
    edges[1].loop = store::LoopStats{123, 0.75, 0.0125, true};
    edges[2].kind = EdgeKind::kPrior;
    edges[2].from_keyframe = b_ids[0];
    edges[2].T_from_to = samplePose(9);
    store.addEdges(edges);
    store.setOptimisedPoses({{ids[1], samplePose(11)}});
    store.setSessionAlignment(b, samplePose(12));
    store.setFeatures(ids[1], features);
    store.attachResource(a, ids[0], store::ResourceKind::kDepth, image.string(),
                         store::AttachMode::kReference);
    store.attachResource(b, std::nullopt, store::ResourceKind::kTsdfLayer, image.string(),
                         store::AttachMode::kCopy);
  }
  Store store(db_path.string(), {false, 0});
  const auto sessions = store.sessions();
  ASSERT_EQ(sessions.size(), 2u);
  EXPECT_EQ(sessions[0].name, "mission_a");
  EXPECT_EQ(sessions[0].source_folder, (dir / "a").string());
  EXPECT_FALSE(sessions[0].aligned);
  EXPECT_FALSE(sessions[0].T_W_S.has_value());
  EXPECT_GT(sessions[0].created_unix_s, 1.6e9);
  EXPECT_TRUE(sessions[1].aligned);
  ASSERT_TRUE(sessions[1].T_W_S.has_value());
  EXPECT_TRUE(sessions[1].T_W_S->isApprox(samplePose(12), 1e-12));

  const auto keyframes = store.keyframes(sessions[0].id);
  ASSERT_EQ(keyframes.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(keyframes[i].timestamp_s, 100.0 + 0.5 * i);
    EXPECT_TRUE(keyframes[i].T_S_C.isApprox(samplePose(i), 1e-12)) << i;
  }
  ASSERT_TRUE(keyframes[1].covariance.has_value());
  EXPECT_EQ(*keyframes[1].covariance, covariance);
  EXPECT_FALSE(keyframes[0].covariance.has_value());
  ASSERT_TRUE(keyframes[1].T_W_C.has_value());  // set by setOptimisedPoses
  EXPECT_TRUE(keyframes[1].T_W_C->isApprox(samplePose(11), 1e-12));
  ASSERT_TRUE(keyframes[2].T_W_C.has_value());  // handed in with the keyframe
  EXPECT_TRUE(keyframes[2].T_W_C->isApprox(samplePose(7), 1e-12));
  EXPECT_FALSE(keyframes[0].T_W_C.has_value());

  const auto all_edges = store.edges();
  ASSERT_EQ(all_edges.size(), 3u);
  EXPECT_EQ(all_edges[0].information, information);
  EXPECT_TRUE(all_edges[0].T_from_to.isApprox(samplePose(3), 1e-12));
  const auto loops = store.edges(EdgeKind::kLoop);
  ASSERT_EQ(loops.size(), 1u);
  ASSERT_TRUE(loops[0].loop.has_value());
  EXPECT_EQ(loops[0].loop->inliers, 123);
  EXPECT_DOUBLE_EQ(loops[0].loop->inlier_ratio, 0.75);
  EXPECT_DOUBLE_EQ(loops[0].loop->residual, 0.0125);
  EXPECT_TRUE(loops[0].loop->accepted);
  const auto priors = store.edges(EdgeKind::kPrior);
  ASSERT_EQ(priors.size(), 1u);
  EXPECT_FALSE(priors[0].to_keyframe.has_value());
  EXPECT_TRUE(priors[0].T_from_to.isApprox(samplePose(9), 1e-12));

  const auto stored_features = store.features(keyframes[1].id);
  ASSERT_TRUE(stored_features.has_value());
  EXPECT_EQ(stored_features->format, "orb");
  EXPECT_EQ(stored_features->descriptor_bytes, 32u);
  EXPECT_EQ(stored_features->keypoints_px, features.keypoints_px);
  EXPECT_EQ(stored_features->descriptors, features.descriptors);
  EXPECT_FALSE(store.features(keyframes[0].id).has_value());

  const auto resources = store.resources();
  ASSERT_EQ(resources.size(), 2u);
  EXPECT_EQ(resources[0].relative_path, "depth_0.png");
  EXPECT_EQ(resources[0].byte_size, 1000u);
  EXPECT_EQ(resources[1].relative_path, "map.resources/session_2/tsdf_layer/depth_0.png");
  EXPECT_EQ(store.readResource(resources[1].id), store.readResource(resources[0].id));
  EXPECT_TRUE(store.verifyResources().empty());

  const auto summary = store.summary();
  ASSERT_EQ(summary.size(), 2u);
  EXPECT_EQ(summary[0].keyframes, 3u);
  EXPECT_EQ(summary[0].optimised_keyframes, 2u);
  EXPECT_EQ(summary[0].odometry_edges, 1u);
  EXPECT_EQ(summary[0].loop_edges, 1u);
  EXPECT_EQ(summary[1].prior_edges, 1u);
  EXPECT_DOUBLE_EQ(summary[0].last_timestamp_s - summary[0].first_timestamp_s, 1.0);
  const double path_m = (samplePose(1).translation() - samplePose(0).translation()).norm() +
                        (samplePose(2).translation() - samplePose(1).translation()).norm();
  EXPECT_NEAR(summary[0].path_length_m, path_m, 1e-12);
  fs::remove_all(dir);
}

TEST(Store, ExceptionInsideATransactionRollsEverythingBack) {
  const fs::path dir = freshStoreDir("rollback");
  Store store((dir / "map.sqlite").string());
  const std::int64_t kept = store.addSession("kept", (dir / "kept").string());
  try {
    auto transaction = store.beginTransaction();
    const std::int64_t s = store.addSession("lost", (dir / "lost").string());
    store.addKeyframes(someKeyframes(s, 4));
    throw std::runtime_error("import failed halfway");
  } catch (const std::runtime_error&) {
  }
  ASSERT_EQ(store.sessions().size(), 1u);
  EXPECT_EQ(store.sessions()[0].id, kept);
  // A failing call rolls back its own batch: the edge before the bad one is not kept either.
  const auto ids = store.addKeyframes(someKeyframes(kept, 2));
  std::vector<EdgeRecord> edges(2);
  edges[0].from_keyframe = ids[0];
  edges[0].to_keyframe = ids[1];
  edges[1].from_keyframe = ids[0];
  edges[1].to_keyframe = 999;
  EXPECT_NE(errorOf([&] { store.addEdges(edges); }).find("no keyframe 999"), std::string::npos);
  EXPECT_TRUE(store.edges().empty());
  EXPECT_THROW(store.setOptimisedPoses({{ids[0], samplePose(1)}, {12345, samplePose(2)}}),
               InputError);
  EXPECT_FALSE(store.keyframes(kept)[0].T_W_C.has_value());
  // Contract checks: a prior with a 'to', a loop without statistics.
  EdgeRecord prior;
  prior.kind = EdgeKind::kPrior;
  prior.from_keyframe = ids[0];
  prior.to_keyframe = ids[1];
  EXPECT_THROW(store.addEdges({prior}), InputError);
  EdgeRecord loop;
  loop.kind = EdgeKind::kLoop;
  loop.from_keyframe = ids[0];
  loop.to_keyframe = ids[1];
  EXPECT_THROW(store.addEdges({loop}), InputError);
  EXPECT_THROW(store.addSession("again", (dir / "kept").string()), InputError);
  store::FeatureSet features;  // 2 keypoints, descriptors for 1
  features.descriptor_bytes = 4;
  features.keypoints_px = {{1.0f, 2.0f}, {3.0f, 4.0f}};
  features.descriptors.resize(4);
  EXPECT_THROW(store.setFeatures(ids[0], features), InputError);
  // Nested batches commit with the outermost one.
  {
    auto outer = store.beginTransaction();
    store.addEdges({edges[0]});
    outer.commit();
  }
  EXPECT_EQ(store.edges().size(), 1u);
  fs::remove_all(dir);
}

TEST(Store, EmptyVersionZeroFileIsMigratedToTheCurrentVersion) {
  const fs::path dir = freshStoreDir("v0");
  const fs::path db = dir / "map.sqlite";
  std::ofstream(db).close();  // an empty file is a valid SQLite database at user_version 0
  {
    Store store(db.string(), {false, 0});
    store.addSession("s", (dir / "s").string());
  }
  store::Database raw(db.string(), false);
  EXPECT_EQ(raw.queryInt("PRAGMA user_version", "test"), store::kSchemaVersion);
  EXPECT_EQ(raw.queryInt("PRAGMA application_id", "test"), store::kApplicationId);
  EXPECT_EQ(raw.queryInt("SELECT COUNT(*) FROM sessions", "test"), 1);
  fs::remove_all(dir);
}

TEST(Store, VersionOneFileIsMigratedKeepingItsSessions) {
  const fs::path dir = freshStoreDir("v1");
  const fs::path db = dir / "map.sqlite";
  {
    Store store(db.string());
    store.addSession("s", (dir / "s").string());
  }
  // What a build of schema version 1 left: no object_database table.
  execSql(db, "DROP TABLE object_database; PRAGMA user_version = 1");
  {
    Store store(db.string(), {false, 0});
    EXPECT_EQ(store.sessions().size(), 1u);
    EXPECT_FALSE(store.objectDatabase().has_value());
    store.setObjectDatabase({1, {1, 2, 3}});
  }
  store::Database raw(db.string(), false);
  EXPECT_EQ(raw.queryInt("PRAGMA user_version", "test"), store::kSchemaVersion);
  fs::remove_all(dir);
}

TEST(Store, ObjectDatabaseBlobIsReplacedWholeAndReadBack) {
  const fs::path dir = freshStoreDir("objects");
  const fs::path db = dir / "map.sqlite";
  {
    Store store(db.string());
    EXPECT_FALSE(store.objectDatabase().has_value());
    store.setObjectDatabase({1, {1, 2, 3}});
    store.setObjectDatabase({1, {4, 5}});
    EXPECT_THROW(store.setObjectDatabase({0, {1}}), InputError);
    EXPECT_THROW(store.setObjectDatabase({1, {}}), InputError);
  }
  Store store(db.string(), {false, 0});
  const auto blob = store.objectDatabase();
  ASSERT_TRUE(blob.has_value());
  EXPECT_EQ(blob->format_version, 1u);
  EXPECT_EQ(blob->bytes, (std::vector<std::uint8_t>{4, 5}));
  fs::remove_all(dir);
}

TEST(Store, FutureSchemaVersionIsRefusedNamingBothVersions) {
  const fs::path dir = freshStoreDir("future");
  const fs::path db = dir / "map.sqlite";
  { Store store(db.string()); }
  execSql(db, "PRAGMA user_version = 7");
  const std::vector<std::uint8_t> before = readFile(db.string());
  const std::string message = errorOf([&] { Store store(db.string()); });
  EXPECT_EQ(readFile(db.string()), before);  // refused before any write
  EXPECT_NE(message.find(db.string()), std::string::npos) << message;
  EXPECT_NE(message.find("version 7"), std::string::npos) << message;
  EXPECT_NE(message.find("version " + std::to_string(store::kSchemaVersion)), std::string::npos)
      << message;
  EXPECT_THROW(Store store(db.string()), InputError);
  fs::remove_all(dir);
}

TEST(Store, SqliteFileOfAnotherApplicationIsRefused) {
  const fs::path dir = freshStoreDir("foreign");
  const fs::path db = dir / "other.sqlite";
  execSql(db, "CREATE TABLE contacts (name TEXT)");
  const std::vector<std::uint8_t> before = readFile(db.string());
  const std::string message = errorOf([&] { Store store(db.string()); });
  EXPECT_EQ(readFile(db.string()), before);  // still in its own journal mode, untouched
  EXPECT_NE(message.find("not a Strata map"), std::string::npos) << message;
  fs::remove_all(dir);
}

TEST(Store, MissingRandomAndTruncatedFilesAreRefusedNamingTheFile) {
  const fs::path dir = freshStoreDir("damaged");
  const fs::path missing = dir / "missing.sqlite";
  std::string message = errorOf([&] { Store store(missing.string(), {false, 0}); });
  EXPECT_NE(message.find(missing.string()), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(missing));
  EXPECT_THROW(Store store((dir / "no_folder" / "map.sqlite").string()), InputError);

  const fs::path random = dir / "random.sqlite";
  writeRandomFile(random, 8192, 7);
  message = errorOf([&] { Store store(random.string()); });
  EXPECT_NE(message.find(random.string()), std::string::npos) << message;
  EXPECT_NE(message.find("not a database"), std::string::npos) << message;
  EXPECT_THROW(Store store(random.string()), InputError);

  const fs::path truncated = dir / "truncated.sqlite";
  {
    Store store(truncated.string());
    const std::int64_t s = store.addSession("big", (dir / "big").string());
    store.addKeyframes(someKeyframes(s, 3000));
  }
  const auto full_size = fs::file_size(truncated);
  ASSERT_GT(full_size, 100000u);
  for (const std::uintmax_t size : {full_size / 2, std::uintmax_t{50}}) {
    fs::resize_file(truncated, size);
    message = errorOf([&] { Store store(truncated.string()); });
    EXPECT_NE(message.find(truncated.string()), std::string::npos) << size << ": " << message;
    EXPECT_THROW(Store store(truncated.string()), InputError) << size;
  }
  fs::remove_all(dir);
}

TEST(Store, FullDatabaseFailsTheBatchAndKeepsWhatWasCommitted) {
  const fs::path dir = freshStoreDir("full");
  const fs::path db = dir / "map.sqlite";
  {
    Store store(db.string());
    const std::int64_t s = store.addSession("small", (dir / "small").string());
    store.addKeyframes(someKeyframes(s, 10));
  }
  {
    Store store(db.string(), {true, 128 * 1024});
    const std::int64_t s = store.sessions()[0].id;
    const std::string message = errorOf([&] { store.addKeyframes(someKeyframes(s, 20000)); });
    EXPECT_NE(message.find(db.string()), std::string::npos) << message;
    EXPECT_NE(message.find("full"), std::string::npos) << message;
    EXPECT_EQ(store.keyframes(s).size(), 10u);  // still usable, nothing half written
  }
  Store store(db.string());
  ASSERT_EQ(store.sessions().size(), 1u);
  EXPECT_EQ(store.keyframes(store.sessions()[0].id).size(), 10u);
  fs::remove_all(dir);
}

/// Opens a new map in a folder without write permission: 0 when refused naming the file.
/// Then writes to an existing map there (the WAL journal needs files beside it).
int tryReadOnlyFolder(const fs::path& dir) {
  int failures = 0;
  for (const char* name : {"map.sqlite", "existing.sqlite"}) {
    const fs::path db = dir / name;
    const std::string message = errorOf([&] {
      Store store(db.string());
      store.addSession("s", "/somewhere");
    });
    std::printf("read-only folder: %s\n", message.c_str());
    failures += message.find(db.string()) != std::string::npos ? 0 : 1;
  }
  return failures;
}

TEST(Store, ReadOnlyFolderIsRefusedNamingTheFile) {
  const fs::path dir = freshStoreDir("read_only");
  { Store store((dir / "existing.sqlite").string()); }
  fs::permissions(dir / "existing.sqlite", fs::perms::all);
  fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                           fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
  int result = 0;
  if (::geteuid() != 0) {
    result = tryReadOnlyFolder(dir);
  } else {
    // Root ignores folder permissions: try as the unprivileged user 'nobody' in a child.
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      if (::setgid(65534) != 0 || ::setuid(65534) != 0) ::_exit(3);
      std::fflush(stdout);
      const int code = tryReadOnlyFolder(dir);
      std::fflush(stdout);
      ::_exit(code);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status));
    result = WEXITSTATUS(status);
  }
  fs::permissions(dir, fs::perms::owner_all);
  EXPECT_EQ(result, 0) << "the error did not name the file (see the printed message)";
  EXPECT_FALSE(fs::exists(dir / "map.sqlite"));
  EXPECT_TRUE(Store((dir / "existing.sqlite").string()).sessions().empty());
  fs::remove_all(dir);
}

TEST(Store, ChangedMissingAndResizedResourcesAreReported) {
  const fs::path dir = freshStoreDir("resources");
  Store store((dir / "map.sqlite").string());
  const std::int64_t s = store.addSession("s", (dir / "s").string());
  std::vector<fs::path> files;
  for (int i = 0; i < 4; ++i) {
    files.push_back(dir / ("file_" + std::to_string(i) + ".bin"));
    writeRandomFile(files.back(), 4096, static_cast<unsigned>(i));
    store.attachResource(s, std::nullopt, store::ResourceKind::kColor, files.back().string(),
                         store::AttachMode::kReference);
  }
  EXPECT_TRUE(store.verifyResources(s).empty());
  writeRandomFile(files[1], 4096, 99);  // same size, other bytes
  fs::remove(files[2]);
  fs::resize_file(files[3], 100);
  const auto problems = store.verifyResources();
  ASSERT_EQ(problems.size(), 3u);
  EXPECT_EQ(problems[0].kind, store::ResourceProblem::Kind::kChecksumChanged);
  EXPECT_EQ(problems[1].kind, store::ResourceProblem::Kind::kMissing);
  EXPECT_EQ(problems[2].kind, store::ResourceProblem::Kind::kSizeChanged);
  EXPECT_NE(problems[0].message.find(files[1].string()), std::string::npos) << problems[0].message;
  const std::string message = errorOf([&] { store.readResource(problems[0].resource.id); });
  EXPECT_NE(message.find("changed"), std::string::npos) << message;
  EXPECT_NE(message.find(files[1].string()), std::string::npos) << message;
  EXPECT_EQ(store.readResource(1).size(), 4096u);  // the unchanged one reads
  fs::remove_all(dir);
}

}  // namespace
}  // namespace strata::test
