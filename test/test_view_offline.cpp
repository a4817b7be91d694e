// What `strata view` serves from a run folder (view/offline_view.h: meshes, paths, session
// trajectories; a malformed file fails it whole) and its bad input (exit 2 before serving, named,
// nothing written). Host only: no .strata map, so no device.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "strata/core/error.h"
#include "strata/mesh/ply.h"
#include "view/offline_view.h"
#include "view/scene.h"
#include "view/server.h"
#include "view/view_command.h"
#include "view/wire.h"

namespace strata::view {
namespace {

namespace fs = std::filesystem;

// A run folder as strata plan and strata align leave them: a mesh, a path, session trajectories one
// folder down; each becomes a scene item, and a malformed path file fails the whole view.
TEST(ViewOffline, RunFoldersGiveMeshesPathsAndSessionTrajectories) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("strata_view_run_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "session_1");
  Mesh triangle;
  triangle.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  triangle.triangles = {{0, 1, 2}};
  writePly((dir / "static_mesh.ply").string(), triangle);
  std::ofstream(dir / "path.csv") << "x,y,z\n0,0,1\n0.5,0,1\n1,0.5,1.2\n";
  std::ofstream(dir / "session_1" / "trajectory.txt")
      << "# t tx ty tz qx qy qz qw\n0 0 0 1 0 0 0 1\n0.1 0.1 0 1 0 0 0 1\n0.2 0.2 0 1 0 0 0 1\n0.3 0.3 0.1 1 0 0 0 1\n";
  Scene scene;
  OfflineView view(dir.string(), "", scene);
  EXPECT_FALSE(view.hasEsdf());
  const Message path = scene.get("path:path.csv");
  ASSERT_NE(path, nullptr) << view.summary();
  EXPECT_EQ(decodeMessage(*path).header["arrays"][0]["count"], 9);
  const Message trajectory = scene.get("trajectory:session_1/trajectory.txt");
  ASSERT_NE(trajectory, nullptr) << view.summary();
  const DecodedMessage t = decodeMessage(*trajectory);
  EXPECT_EQ(t.header["arrays"][0]["count"], 12);
  float last[3];
  std::memcpy(last, t.payload.data() + 9 * sizeof(float), sizeof(last));
  EXPECT_FLOAT_EQ(last[0], 0.3f);
  EXPECT_FLOAT_EQ(last[1], 0.1f);
  EXPECT_FLOAT_EQ(last[2], 1.0f);
  ASSERT_NE(scene.get("mesh:static_mesh"), nullptr);
  // An answer without a map says why.
  EXPECT_EQ(decodeMessage(*view.answer({{"type", "query"}, {"point", {0, 0, 0}}})).header["type"], "error");

  std::ofstream(dir / "path.csv") << "x,y,z\n0,0,1\n0,nan,1\n";
  Scene other;
  EXPECT_THROW(OfflineView(dir.string(), "", other), InputError);
  EXPECT_EQ(other.size(), 0u) << "a view that failed put something in its scene";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace strata::view

namespace strata::apps {
namespace {

namespace fs = std::filesystem;

// `strata view` refuses bad input before any work, exit 2, naming the problem, and writes nothing.
TEST(ViewCommand, BadInputExitsTwoBeforeServing) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("strata_view_cli_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "empty");
  const std::string text = (dir / "notes.txt").string();
  std::ofstream(text) << "not a map";
  const std::string bad_map = (dir / "bad.strata").string();
  std::ofstream(bad_map) << "STRATA?";
  auto run = [](ViewOptions o) {
    o.quiet = true;
    o.port = 0;
    return runView(o);
  };
  ViewOptions o;
  o.path = (dir / "missing.strata").string();
  EXPECT_EQ(run(o), 2);
  o.path = text;
  EXPECT_EQ(run(o), 2);
  o.path = (dir / "empty").string();
  EXPECT_EQ(run(o), 2);
  o.path = bad_map;
  EXPECT_EQ(run(o), 2);
  ViewOptions shot_over_input;
  shot_over_input.path = bad_map;
  shot_over_input.screenshot_path = bad_map;
  EXPECT_EQ(run(shot_over_input), 2);
  EXPECT_EQ(fs::file_size(bad_map), 7u) << "an input was written";
  ViewOptions bad_port;
  bad_port.path = text;
  bad_port.port = 70000;
  EXPECT_EQ(runView(bad_port), 2);
  // A mesh to serve, and addresses that cannot be served on.
  Mesh triangle;
  triangle.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  triangle.triangles = {{0, 1, 2}};
  const std::string ply = (dir / "triangle.ply").string();
  writePly(ply, triangle);
  ViewOptions bad_bind;
  bad_bind.path = ply;
  bad_bind.quiet = true;
  bad_bind.bind_address = "localhost:80";
  EXPECT_EQ(runView(bad_bind), 2);
  view::Scene scene;
  view::ServerOptions taken_options;
  taken_options.port = 0;
  view::Server taken(scene, taken_options);
  taken.start();
  ViewOptions in_use;
  in_use.path = ply;
  in_use.quiet = true;
  in_use.port = taken.port();
  EXPECT_EQ(runView(in_use), 2);
  // The same mesh on a free port, served for a moment: exit 0.
  ViewOptions fine;
  fine.path = ply;
  fine.quiet = true;
  fine.port = 0;
  fine.serve_seconds = 0.2;
  EXPECT_EQ(runView(fine), 0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace strata::apps
