#include "strata/select/eval/map_history.h"

#include "strata/core/error.h"
#include "strata/map/block_index.h"

namespace strata::selection {

MapHistory::MapHistory(float cell_m) : cell_m_(cell_m) {
  if (!(cell_m > 0.0f)) throw InputError("MapHistory: cell_m must be > 0");
}

std::uint64_t MapHistory::cellKey(const Eigen::Vector3f& p_W) const {
  // The block index's key: 21 bits per axis, ±1 M cells (±100 km at 10 cm).
  return packBlockKey((p_W / cell_m_).array().floor().cast<int>().matrix());
}

void MapHistory::addSession(std::unique_ptr<sim::RayScene> scene,
                            const std::vector<Eigen::Vector3f>& fused_surface_W) {
  if (!scene) throw InputError("MapHistory::addSession: no scene");
  Session s;
  s.scene = std::move(scene);
  for (const Eigen::Vector3f& p_W : fused_surface_W) s.seen_cells.insert(cellKey(p_W));
  sessions_.push_back(std::move(s));
}

std::vector<float> MapHistory::lastObservedDistance(const std::vector<sim::Ray>& rays) const {
  std::vector<float> distance_m(rays.size(), -1.0f);
  std::vector<std::uint8_t> resolved(rays.size(), 0);
  std::vector<sim::RayHit> hits;
  for (auto s = sessions_.rbegin(); s != sessions_.rend(); ++s) {
    s->scene->intersect(rays, hits);
    for (std::size_t i = 0; i < rays.size(); ++i) {
      if (resolved[i] || !hits[i].hit()) continue;
      const Eigen::Vector3f p_W = rays[i].origin_W + hits[i].t_m * rays[i].direction_W;
      if (!s->seen_cells.count(cellKey(p_W))) continue;  // an older session may have seen it
      distance_m[i] = hits[i].t_m;
      resolved[i] = 1;
    }
  }
  return distance_m;
}

}  // namespace strata::selection
