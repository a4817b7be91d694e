#include "strata/objects/object_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <unordered_set>

#include "strata/core/error.h"
#include "strata/mesh/extract_mesh.h"
#include "strata/objects/internal/cloud_stats.h"
#include "strata/objects/internal/block_sets.h"

namespace strata::objects {
namespace {

// A sample closer than this (in voxels) to a grid plane lies on it: its corners beyond the plane
// carry no weight and need not be observed. This keeps a merge on the model's own grid exact.
constexpr double kOnGridVoxels = 1e-4;

Eigen::Vector3f unpackColor(std::uint32_t rgba) {
  return Eigen::Vector3f(static_cast<float>(rgba & 0xffu), static_cast<float>((rgba >> 8) & 0xffu),
                         static_cast<float>((rgba >> 16) & 0xffu));
}

std::uint32_t packColor(const Eigen::Vector3f& c) {
  const auto channel = [](float v) {
    return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
  };
  return packRgb(channel(c.x()), channel(c.y()), channel(c.z()));
}

MapConfig modelMapConfig(const MapConfig& observation, const ObjectModelConfig& config) {
  MapConfig out = observation;
  const float truncation_m = observation.truncationDistance();
  if (config.voxel_size_m > 0.0f) out.voxel_size_m = config.voxel_size_m;
  out.truncation_voxels = truncation_m / out.voxel_size_m;  // keep the band's width in metres
  out.dropoff_start_voxels = std::min(out.dropoff_start_voxels, 0.5f * out.truncation_voxels);
  out.max_weight = config.max_weight;
  out.validate();
  return out;
}

void requireFinite(const Eigen::Isometry3d& T, const char* what) {
  if (!T.matrix().allFinite()) {
    throw InputError(std::string("object model: ") + what + " is not finite");
  }
}

/// Model blocks that may receive a sample of the observation: those its blocks' boxes cover
/// once mapped into M.
std::vector<BlockIndex> coveredBlocks(const TsdfMap& model, const TsdfMap& observation,
                                      const Eigen::Isometry3d& T_M_O) {
  BlockSet blocks;
  for (const auto& entry : model.blocks()) blocks.insert(entry.first);
  const double obs_block_m = observation.config().blockSize();
  const double model_block_m = model.config().blockSize();
  for (const auto& entry : observation.blocks()) {
    Eigen::AlignedBox3d box;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d corner((entry.first.x() + (c & 1)) * obs_block_m,
                                   (entry.first.y() + ((c >> 1) & 1)) * obs_block_m,
                                   (entry.first.z() + ((c >> 2) & 1)) * obs_block_m);
      box.extend(T_M_O * corner);
    }
    const Eigen::Vector3i lo = (box.min() / model_block_m).array().floor().cast<int>();
    const Eigen::Vector3i hi = (box.max() / model_block_m).array().floor().cast<int>();
    insertBlocksInBox(lo, hi, blocks);
  }
  return sortedBlocks(blocks);
}

/// Weighted average of one sample into one voxel, the weight capped.
void fuseSample(TsdfVoxel& voxel, const TsdfSample& sample, float max_weight) {
  const float w_m = voxel.weight, w_o = sample.weight;
  const float w = w_m + w_o;
  voxel.tsdf_m = (w_m * voxel.tsdf_m + w_o * sample.distance_m) / w;
  voxel.color_rgba = packColor((w_m * unpackColor(voxel.color_rgba) + w_o * sample.color) / w);
  voxel.weight = std::min(w, max_weight);
}

}  // namespace

void ObjectModelConfig::validate() const {
  auto fail = [](const std::string& what) {
    throw InputError("invalid object model config: " + what);
  };
  if (!std::isfinite(voxel_size_m) || voxel_size_m < 0.0f ||
      (voxel_size_m > 0.0f && (voxel_size_m < 0.001f || voxel_size_m > 1.0f))) {
    fail("voxel_size_m must be 0 (the map's) or in [0.001, 1] m");
  }
  if (!std::isfinite(max_weight) || max_weight <= 0.0f) fail("max_weight must be > 0");
  if (!std::isfinite(min_weight) || min_weight < 0.0f || min_weight >= max_weight) {
    fail("min_weight must be in [0, max_weight)");
  }
}

std::optional<TsdfSample> sampleTsdf(const TsdfMap& map, const Eigen::Vector3f& p,
                                     float min_weight) {
  const double voxel_m = map.config().voxel_size_m;
  // Voxel centres sit at (i + 0.5) * voxel: q is p in units of the centre grid.
  const Eigen::Vector3d q = p.cast<double>() / voxel_m - Eigen::Vector3d::Constant(0.5);
  Eigen::Vector3i base = q.array().floor().cast<int>();
  Eigen::Vector3d frac = q - base.cast<double>();
  for (int k = 0; k < 3; ++k) {
    if (frac[k] > 1.0 - kOnGridVoxels) {
      ++base[k];
      frac[k] = 0.0;
    } else if (frac[k] < kOnGridVoxels) {
      frac[k] = 0.0;
    }
  }
  TsdfSample out;
  out.weight = std::numeric_limits<float>::infinity();
  double distance = 0.0;
  Eigen::Vector3d color = Eigen::Vector3d::Zero();
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3i corner((c & 1), (c >> 1) & 1, (c >> 2) & 1);
    double w = 1.0;
    for (int k = 0; k < 3; ++k) w *= corner[k] ? frac[k] : 1.0 - frac[k];
    if (w == 0.0) continue;
    const TsdfVoxel* voxel = map.findVoxel(base + corner);
    if (voxel == nullptr || voxel->weight < min_weight || voxel->weight <= 0.0f) {
      return std::nullopt;
    }
    distance += w * voxel->tsdf_m;
    color += w * unpackColor(voxel->color_rgba).cast<double>();
    out.weight = std::min(out.weight, voxel->weight);
  }
  out.distance_m = static_cast<float>(distance);
  out.color = color.cast<float>();
  return out;
}

ObjectModel foundModel(int id, const ObjectObservation& observation,
                       const ObjectModelConfig& config) {
  config.validate();
  ObjectModel model;
  model.id = id;
  model.tsdf = TsdfMap(modelMapConfig(observation.tsdf.config(), config));
  const float obs_voxel_m = observation.tsdf.config().voxel_size_m;
  if (model.tsdf.config().voxel_size_m == obs_voxel_m) {
    for (const auto& [b, block] : observation.tsdf.blocks()) {
      TsdfBlock& out = model.tsdf.allocateBlock(b);
      out = block;
      for (TsdfVoxel& v : out) v.weight = std::min(v.weight, config.max_weight);
    }
  } else {
    mergeObservation(model, observation, Eigen::Isometry3d::Identity(), config);
  }
  model.merged_observations = 1;
  ObjectInstance instance;
  instance.session = observation.session;
  instance.segment_id = observation.segment_id;
  instance.T_W_M = observation.T_W_O;
  instance.observed_area_m2 = observation.surface_area_m2;
  instance.merged = true;
  model.instances.push_back(instance);
  refreshModel(model, obs_voxel_m, config);
  return model;
}

void mergeObservation(ObjectModel& model, const ObjectObservation& observation,
                      const Eigen::Isometry3d& T_M_O, const ObjectModelConfig& config) {
  config.validate();
  requireFinite(T_M_O, "T_M_O");
  const float model_voxel_m = model.tsdf.config().voxel_size_m;
  const float obs_min_weight = std::max(config.min_weight, std::numeric_limits<float>::min());
  const Eigen::Isometry3d T_O_M = T_M_O.inverse();
  for (const BlockIndex& b : coveredBlocks(model.tsdf, observation.tsdf, T_M_O)) {
    const TsdfBlock* existing = model.tsdf.findBlock(b);
    TsdfBlock block = existing ? *existing : TsdfBlock{};
    bool touched = false;
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      const GlobalVoxelIndex v = voxelOfBlock(b, i);
      const Eigen::Vector3d p_M = voxelCenter(v, model_voxel_m).cast<double>();
      const auto sample = sampleTsdf(observation.tsdf, (T_O_M * p_M).cast<float>(), obs_min_weight);
      if (!sample) continue;
      fuseSample(block[static_cast<std::size_t>(i)], *sample, config.max_weight);
      touched = true;
    }
    if (touched) model.tsdf.allocateBlock(b) = block;
  }
}

void refreshModel(ObjectModel& model, float sample_spacing_m, const ObjectModelConfig& config) {
  config.validate();
  MeshOptions options;
  options.min_weight = config.min_weight;
  options.num_threads = 1;  // models are small; the database may refresh several in parallel
  model.mesh_M = extractMesh(model.tsdf, options);
  model.surface_M = sampleSurface(model.mesh_M, sample_spacing_m);
  model.extent_m = boundingExtent(model.surface_M);
  model.surface_area_m2 = meshArea(model.mesh_M);
  model.mean_color = meanColor(model.surface_M);
}

float meshArea(const Mesh& mesh) {
  double area = 0.0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[static_cast<std::size_t>(t.x())].cast<double>();
    const Eigen::Vector3d b = mesh.vertices[static_cast<std::size_t>(t.y())].cast<double>();
    const Eigen::Vector3d c = mesh.vertices[static_cast<std::size_t>(t.z())].cast<double>();
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return static_cast<float>(area);
}

}  // namespace strata::objects
