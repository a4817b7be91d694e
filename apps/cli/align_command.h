#pragma once
// `strata align`: multi-session alignment (src/strata/align, docs/align.md).
//   strata align SESSION_DIR... --out DIR   imports the folders into DIR/map.sqlite (the first
//                                           anchors the world frame), then aligns
//   strata align --db map.sqlite [--out DIR] aligns the sessions of an existing map database
// Writes DIR/session_K/trajectory.txt (every frame, TUM, camera-to-world in the common frame; K
// is the session's place in the map, 0 = the anchor; none for a session left unaligned),
// loops.csv, report.json and trajectories.png (top-down, before and after, loops drawn). When
// every folder has groundtruth.txt beside the odometry.txt it aligned, report.json also scores
// the result against it (ATE before/after, loops checked against the truth).
// Options and paths (outputs against the session folders and the database) are checked before
// anything is read or made. The imports, the alignment and the files are one transaction of the
// database: a failed run leaves it as it was (no half-made session for the next `align --db`)
// and no output behind.
// Exit 0 done (also when a session stays unaligned: reported), 2 bad input, 1 other failures.
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace strata::apps {

struct AlignOptions {
  std::vector<std::string> session_dirs;
  std::string db_path;  // default with folders: DIR/map.sqlite
  std::string out_dir;  // default with --db: the database's folder
  int keyframe_every = 10;
  double keyframe_distance_m = 0.0;
  double odometry_sigma_m = 0.01;    // import: odometry edge noise (store/session_import.h)
  double odometry_sigma_rad = 0.01;
  int candidates = 4;
  double intra_gap_s = 15.0;
  bool no_intra = false;
  bool no_truth = false;
  int threads = 2;
  bool quiet = false;
};

CLI::App* addAlignCommand(CLI::App& app, AlignOptions& options);
int runAlign(const AlignOptions& options);

}  // namespace strata::apps
