#pragma once
// The files `strata align` writes (all atomically): per-session trajectories, loops.csv,
// report.json, and the truth the report scores against.
#include <optional>
#include <string>
#include <vector>

#include "strata/align/alignment_eval.h"
#include "strata/align/store_alignment.h"

namespace strata::apps {

/// DIR/session_K/trajectory.txt for every aligned session; returns the files written.
std::vector<std::string> writeAlignedTrajectories(const align::StoreAlignment& a,
                                                  const std::string& out_dir);

/// loops.csv: one row per verified loop: sessions and keyframes (index and timestamp), the
/// verifier's figures, the graph's switch and decision, and with a score the error against the
/// truth.
void writeLoopsCsv(const align::StoreAlignment& a, const align::AlignmentScore* score,
                   const std::string& path);

/// report.json: sessions (name, folder, odometry file, keyframes, aligned, T_W_S), loop counts,
/// rejection reasons, stage times, the pose graph's figures, and the score when there is one.
void writeAlignReport(const align::StoreAlignment& a, const align::AlignmentScore* score,
                      const std::string& db_path, double total_s, const std::string& path);

}  // namespace strata::apps
