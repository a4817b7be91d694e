#include "cli/objects_before_after.h"

#include <algorithm>
#include <string>

#include "cli/esdf_slice_font.h"
#include "cli/objects_sheet.h"
#include "strata/objects/object_observation.h"

namespace strata::apps {
namespace {

constexpr Rgb kPairText = {20, 20, 20};
constexpr int kPairLabelHeightPx = 22;
constexpr int kPairGapPx = 4;

/// The models to show: two observations or more, most merged observations first (then larger).
std::vector<const objects::ObjectModel*> mergedModels(const objects::ObjectDatabase& db,
                                                      int count) {
  std::vector<const objects::ObjectModel*> models;
  for (const objects::ObjectModel& m : db.models()) {
    if (m.merged_observations > 1 && !m.mesh_M.vertices.empty()) models.push_back(&m);
  }
  std::stable_sort(models.begin(), models.end(), [](const auto* a, const auto* b) {
    return a->merged_observations != b->merged_observations
               ? a->merged_observations > b->merged_observations
               : a->surface_area_m2 > b->surface_area_m2;
  });
  if (models.size() > static_cast<std::size_t>(count)) models.resize(count);
  return models;
}

/// The model's largest single observation, rendered with the model's camera (dark grey when its
/// segment cannot be found or re-observed).
ColorImage renderLargestObservation(const objects::ObjectModel& model, const DiffResult& result,
                                    const std::vector<TsdfMap>& maps,
                                    const objects::ObservationConfig& config, int size_px) {
  const auto largest = std::max_element(
      model.instances.begin(), model.instances.end(),
      [](const auto& a, const auto& b) { return a.observed_area_m2 < b.observed_area_m2; });
  const auto s = static_cast<std::size_t>(largest->session);
  if (s >= result.sessions.size() || s >= maps.size()) return ColorImage(size_px, size_px, 60);
  const DiffSession& session = result.sessions[s];
  for (const change::DiscoveredObject& segment : session.objects) {
    if (segment.id != largest->segment_id) continue;
    const objects::ObjectObservation o =
        objects::observeObject(maps[s], session.surface, segment, largest->session, config);
    const ModelCamera camera = modelCamera(model, size_px);
    const Eigen::Isometry3d T_O_M = o.T_W_O.inverse() * largest->T_W_M;
    return renderTsdfView(o.tsdf, camera.intrinsics, T_O_M * camera.T_M_C);
  }
  return ColorImage(size_px, size_px, 60);
}

}  // namespace

ColorImage renderBeforeAfter(const ObjectsRun& run, const DiffResult& result,
                             const std::vector<TsdfMap>& maps, int count, int size_px) {
  const std::vector<const objects::ObjectModel*> models = mergedModels(run.database, count);
  if (models.empty()) {
    ColorImage empty(360, 40, 255);
    drawText(empty, 8, 12, "NO MODEL WAS MERGED", 2, kPairText);
    return empty;
  }
  const int columns = static_cast<int>(models.size());
  const int row_px = size_px + kPairLabelHeightPx + kPairGapPx;
  ColorImage sheet(columns * (size_px + kPairGapPx) + kPairGapPx, 2 * row_px + kPairGapPx, 255);
  for (int i = 0; i < columns; ++i) {
    const objects::ObjectModel& m = *models[static_cast<std::size_t>(i)];
    const int x0 = kPairGapPx + i * (size_px + kPairGapPx);
    drawText(sheet, x0 + 2, kPairGapPx + 4, "MODEL " + std::to_string(m.id) + ": LARGEST VIEW", 1,
             kPairText);
    pasteTile(sheet,
              renderLargestObservation(m, result, maps, run.database.config().observation, size_px),
              x0, kPairGapPx + kPairLabelHeightPx);
    drawText(sheet, x0 + 2, kPairGapPx + row_px + 4,
             "MERGED: " + std::to_string(m.merged_observations) + " OBSERVATIONS", 1, kPairText);
    pasteTile(sheet, renderModelView(m, size_px), x0, kPairGapPx + row_px + kPairLabelHeightPx);
  }
  return sheet;
}

}  // namespace strata::apps
