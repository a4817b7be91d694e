// strata view's page in a real browser: Debian's headless Chromium, driven by playwright-core
// (test/browser/view_check.cjs), against the offline scene of a fused analytic room served by the
// viewer's server in this process. The page must load with no console error, connect its
// WebSocket, hold the scene's meshes and triangles, draw a picture the surface covers, show the
// ESDF slice, and the distances it reads (by query and by a real click) must be the Mapper's.
// Skips, saying why, where Chromium, Node.js or web/'s npm packages are absent.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "browser_available.h"
#include "fusion_fixture.h"
#include "strata/io/image_io.h"
#include "strata/map/map_file.h"
#include "strata/mapper/mapper.h"
#include "strata/sim/analytic_dataset.h"
#include "test_utils.h"
#include "view/offline_view.h"
#include "view/server.h"

namespace strata::view {
namespace {

namespace fs = std::filesystem;

TEST(ViewBrowser, ThePageShowsTheMapAndReadsTheMappersDistances) {
  const std::string missing = test::browserUnavailable();
  if (!missing.empty()) GTEST_SKIP() << missing;
  const fs::path dir = fs::path(::testing::TempDir()) / ("strata_view_browser_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);

  // The analytic room fused at 4 cm, saved as a map file, served as `strata view MAP` serves it.
  sim::AnalyticDatasetConfig data_config;
  data_config.frame_count = 24;
  const sim::AnalyticDataset dataset(data_config);
  MapConfig map_config;
  map_config.voxel_size_m = 0.04f;
  const TsdfMap map = test::fuseOnDevice(dataset, map_config, dataset.size());
  const std::string map_path = (dir / "room.strata").string();
  saveMap(map, map_path);

  Scene scene;
  OfflineView offline(map_path, "", scene);
  ASSERT_TRUE(offline.hasEsdf());
  ServerOptions options;
  options.port = 0;
  Server server(scene, options, [&offline](const nlohmann::json& r) { return offline.answer(r); });
  server.start();
  const std::string url = "http://127.0.0.1:" + std::to_string(server.port()) + "/";

  // The truth: the same map's ESDF, queried by a Mapper of this test's own.
  MapperConfig config;
  config.map = map.config();
  config.esdf = true;
  const auto truth = Mapper::fromMap(map, test::sharedContext(), config);
  truth->updateEsdf();
  const Mesh mesh = truth->mesh();
  ASSERT_FALSE(mesh.empty());
  Eigen::Vector3f lo = mesh.vertices.front(), hi = lo;
  for (const auto& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Eigen::Vector3f centre = 0.5f * (lo + hi);
  const float slice_z = lo.z() + 0.4f * (hi.z() - lo.z());
  const std::vector<Eigen::Vector3f> points = {centre, centre + Eigen::Vector3f(0.5f, 0.3f, -0.2f),
                                               mesh.vertices[mesh.vertices.size() / 2]};
  nlohmann::json queries = {{"slice_z", slice_z}, {"points", nlohmann::json::array()}};
  for (const auto& p : points) queries["points"].push_back({p.x(), p.y(), p.z()});
  const fs::path queries_path = dir / "queries.json", out_path = dir / "seen.json", shot = dir / "view.png";
  std::ofstream(queries_path) << queries.dump();

  const std::string command = "timeout 240 node '" STRATA_VIEW_CHECK_SCRIPT "' '" STRATA_WEB_DIR "' '" + url +
                              "' '" + out_path.string() + "' '" + shot.string() + "' '" +
                              queries_path.string() + "' 2>&1";
  std::string output;
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char chunk[512];
  while (std::fgets(chunk, sizeof(chunk), pipe)) output += chunk;
  const int status = pclose(pipe);
  ASSERT_EQ(status, 0) << "the browser check failed:\n" << output;
  std::ifstream in(out_path);
  const nlohmann::json seen = nlohmann::json::parse(in);

  EXPECT_TRUE(seen["consoleErrors"].empty()) << seen["consoleErrors"].dump(1);
  EXPECT_TRUE(seen["pageErrors"].empty()) << seen["pageErrors"].dump(1);
  const auto& state = seen["state"];
  EXPECT_TRUE(state["connected"].get<bool>());
  EXPECT_TRUE(state["errors"].empty()) << state["errors"].dump();
  EXPECT_EQ(state["meshes"], 1);
  EXPECT_EQ(state["triangles"].get<std::size_t>(), mesh.triangles.size());
  EXPECT_EQ(state["vertices"].get<std::size_t>(), mesh.vertices.size());
  EXPECT_EQ(state["stats"]["blocks"].get<std::uint32_t>(), truth->blockCount());
  EXPECT_GT(state["slice"]["known"].get<int>(), 100) << "the ESDF slice at " << slice_z << " m shows almost nothing";
  // The browser's own picture: the room covers a good part of the view right of the panel, and
  // not all of it (the framing leaves a margin).
  const ColorImage picture = readColorImage(shot.string());
  ASSERT_EQ(picture.width_px, 1024);
  std::size_t covered = 0, counted = 0;
  for (int y = 0; y < picture.height_px; ++y) {
    for (int x = 280; x < picture.width_px; ++x) {
      const std::uint8_t* p = &picture.rgb[3 * (static_cast<std::size_t>(y) * picture.width_px + x)];
      covered += std::abs(p[0] - 0x1d) + std::abs(p[1] - 0x21) + std::abs(p[2] - 0x26) > 24 ? 1 : 0;
      ++counted;
    }
  }
  const double coverage = static_cast<double>(covered) / counted;
  EXPECT_GT(coverage, 0.05) << "the screenshot is (nearly) blank";  // 0.106 when written
  EXPECT_LT(coverage, 0.9);

  auto expectTheMappers = [&](const nlohmann::json& answer) {
    const Eigen::Vector3f p(answer["point"][0].get<float>(), answer["point"][1].get<float>(),
                            answer["point"][2].get<float>());
    const EsdfSample s = truth->distances({p}).front();
    EXPECT_EQ(answer["known"].get<bool>(), s.status == EsdfStatus::kKnown) << answer.dump();
    if (s.status == EsdfStatus::kKnown) {
      EXPECT_NEAR(answer["distance"].get<float>(), s.distance_m, 1e-5f) << answer.dump();
    }
  };
  ASSERT_EQ(seen["answers"].size(), points.size());
  int known = 0;
  for (const auto& a : seen["answers"]) {
    expectTheMappers(a);
    known += a["known"].get<bool>() ? 1 : 0;
  }
  EXPECT_GE(known, 1) << "no query point had a known distance: the check would test nothing";
  ASSERT_FALSE(seen["click"].is_null()) << "a click in the middle of the framed room hit no surface";
  expectTheMappers(seen["click"]);
  // A click lands on the surface: the distance there is under a voxel or two.
  EXPECT_LT(seen["click"]["distance"].get<float>(), 2.5f * map_config.voxel_size_m);

  server.stop();
  if (!HasFailure()) {
    fs::remove_all(dir);
  } else {
    std::printf("the browser's picture and what it saw are kept in %s\n", dir.c_str());
  }
}

}  // namespace
}  // namespace strata::view
