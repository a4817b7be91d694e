#include "cli/select_outputs.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "cli/select_plot.h"
#include "strata/core/atomic_file.h"
#include "strata/io/image_io.h"

namespace strata::apps {

void writeSelectionCsv(const std::string& path, const std::vector<ScoredKeyframe>& keyframes,
                       const selection::TrajectorySelection& s,
                       const std::vector<selection::KeyframeTruth>& truth) {
  const bool with_truth = !truth.empty();
  if (with_truth && truth.size() != keyframes.size()) {
    throw std::invalid_argument("writeSelectionCsv: one truth per keyframe expected");
  }
  std::string text =
      "index,name,timestamp_s,coverage,color_change,depth_change_m,surface_change,ncc,histogram,"
      "coverage_smoothed,color_change_smoothed,depth_change_m_smoothed,surface_change_smoothed,"
      "similarity_smoothed,triggered,selected";
  text += with_truth ? ",true_changed_fraction,true_unmapped_fraction,true_positive\n" : "\n";
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    const selection::KeyframeScore& k = keyframes[i].score;
    std::string name = keyframes[i].name;
    for (char& c : name) c = c == ',' || c == '\n' ? ' ' : c;  // keep the CSV parseable
    char line[512];
    std::snprintf(line, sizeof(line),
                  "%zu,%s,%.6f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%d,%d\n",
                  i, name.c_str(), keyframes[i].timestamp_s, k.coverage, k.color_change,
                  k.depth_change_m, k.surface_change, k.ncc, k.histogram, s.coverage[i],
                  s.color_change[i], s.depth_change_m[i], s.surface_change[i], s.similarity[i],
                  s.triggered[i], s.selected[i]);
    text += line;
    if (with_truth) {
      const selection::KeyframeTruth& t = truth[i];
      const double valid = std::max(1, t.valid_pixels);
      std::snprintf(line, sizeof(line), ",%.5f,%.5f,%d\n", t.changed_pixels / valid,
                    t.unmapped_pixels / valid, t.positive ? 1 : 0);
      text.pop_back();  // the row goes on after the metrics
      text += line;
    }
  }
  writeFileAtomically(path, std::vector<std::uint8_t>(text.begin(), text.end()));
}

std::vector<std::string> writeSelectionPictures(const std::string& out_dir,
                                                const std::vector<ScoredKeyframe>& keyframes,
                                                const selection::TrajectorySelection& s,
                                                const selection::SelectionConfig& config) {
  const std::filesystem::path out(out_dir);
  const std::string plot = (out / "selection.png").string();
  writeColorPng(plot, renderSelectionPlot(s, config));
  std::vector<ColorImage> thumbnails;
  std::vector<std::size_t> labels;
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    if (!s.selected[i] || keyframes[i].thumbnail.empty()) continue;
    thumbnails.push_back(keyframes[i].thumbnail);
    labels.push_back(i);
  }
  const std::string sheet = (out / "selected.png").string();
  writeColorPng(sheet, renderContactSheet(thumbnails, labels));
  return {plot, sheet};
}

}  // namespace strata::apps
