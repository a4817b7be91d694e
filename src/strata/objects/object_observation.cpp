#include "strata/objects/object_observation.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <string>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "strata/core/error.h"
#include "strata/objects/internal/cloud_stats.h"
#include "strata/objects/internal/block_sets.h"
#include "strata/objects/object_model.h"

namespace strata::objects {
namespace {

using CellKey = std::uint64_t;

CellKey cellKey(const Eigen::Vector3i& c) { return packBlockKey(c); }

Eigen::Vector3i cellOf(const Eigen::Vector3f& p, float cell_m) {
  return (p / cell_m).array().floor().cast<int>();
}

/// Bit pattern of a position: the segment's vertices are copies of the surface's.
struct PositionHash {
  std::size_t operator()(const Eigen::Vector3f& p) const {
    std::uint32_t bits[3];
    std::memcpy(bits, p.data(), sizeof(bits));
    return hashBlockKey(bits[0] ^ (std::uint64_t{bits[1]} << 21) ^ (std::uint64_t{bits[2]} << 42));
  }
};

/// Points in cubic cells of the query radius: a radius query reads the 27 cells around it.
class PointGrid {
 public:
  explicit PointGrid(float cell_m) : cell_m_(cell_m) {}
  void add(const Eigen::Vector3f& p, bool is_segment) {
    cells_[cellKey(cellOf(p, cell_m_))].push_back(points_.size());
    points_.push_back(p);
    segment_.push_back(is_segment);
  }
  /// Whether the nearest point within the cell size of `q` exists and is a segment point.
  bool nearestIsSegment(const Eigen::Vector3f& q) const {
    const Eigen::Vector3i c = cellOf(q, cell_m_);
    float best = cell_m_ * cell_m_;
    bool best_segment = false;
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = cells_.find(cellKey(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (const std::size_t i : it->second) {
            const float d2 = (points_[i] - q).squaredNorm();
            // Ties go to the rest of the surface: a voxel between two objects is nobody's.
            if (d2 < best || (d2 == best && !segment_[i])) {
              best = d2;
              best_segment = segment_[i];
            }
          }
        }
      }
    }
    return best_segment;
  }

 private:
  float cell_m_;
  std::vector<Eigen::Vector3f> points_;
  std::vector<bool> segment_;
  std::unordered_map<CellKey, std::vector<std::size_t>> cells_;
};

PointGrid surfaceGrid(const change::LabelledSurface& surface, const Mesh& segment, float cell_m) {
  PointGrid grid(cell_m);
  std::unordered_set<Eigen::Vector3f, PositionHash> in_segment(segment.vertices.begin(),
                                                               segment.vertices.end());
  for (const Eigen::Vector3f& p : segment.vertices) grid.add(p, true);
  for (const Eigen::Vector3f& p : surface.mesh.vertices) {
    if (in_segment.count(p) == 0) grid.add(p, false);
  }
  return grid;
}

/// Blocks of the session map that may hold voxels within `band_m` of a segment vertex.
std::vector<BlockIndex> candidateBlocks(const Mesh& segment, float band_m, float block_m) {
  BlockSet blocks;
  for (const Eigen::Vector3f& p : segment.vertices) {
    insertBlocksInBox(cellOf(p - Eigen::Vector3f::Constant(band_m), block_m),
                      cellOf(p + Eigen::Vector3f::Constant(band_m), block_m), blocks);
  }
  return sortedBlocks(blocks);
}

/// Copies the session voxels whose nearest surface is the segment's into `out`, shifted by
/// `offset_voxels` (world voxel index - offset = object voxel index).
void copyObjectBand(const TsdfMap& session_map, const change::LabelledSurface& surface,
                    const Mesh& segment, float band_m, const Eigen::Vector3i& offset_voxels,
                    TsdfMap& out) {
  const float voxel_m = session_map.config().voxel_size_m;
  const PointGrid grid = surfaceGrid(surface, segment, band_m);
  for (const BlockIndex& b : candidateBlocks(segment, band_m, session_map.config().blockSize())) {
    const TsdfBlock* block = session_map.findBlock(b);
    if (block == nullptr) continue;
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      const TsdfVoxel& voxel = (*block)[static_cast<std::size_t>(i)];
      if (voxel.weight <= 0.0f) continue;
      const GlobalVoxelIndex v = voxelOfBlock(b, i);
      if (!grid.nearestIsSegment(voxelCenter(v, voxel_m))) continue;
      out.allocateVoxel(v - offset_voxels) = voxel;
    }
  }
}

float singularValueRatio(const SurfaceCloud& cloud) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : cloud.points) mean += p.cast<double>();
  mean /= static_cast<double>(cloud.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : cloud.points) {
    const Eigen::Vector3d d = p.cast<double>() - mean;
    cov += d * d.transpose();
  }
  // Singular values of the centred samples are the square roots of the scatter's eigenvalues.
  const Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvalues();
  if (ev(2) <= 0.0) return 0.0f;
  return static_cast<float>(std::sqrt(std::max(ev(0), 0.0) / ev(2)));
}

void refuseDegenerate(const SurfaceCloud& cloud, const change::DiscoveredObject& segment,
                      const ObservationConfig& config) {
  if (cloud.size() < config.min_samples) {
    std::ostringstream msg;
    msg << "object segment " << segment.id << " of session " << segment.session
        << " is degenerate: too few surface samples (" << cloud.size() << " < min_samples "
        << config.min_samples << ")";
    throw InputError(msg.str());
  }
  const float ratio = singularValueRatio(cloud);
  if (ratio < config.min_singular_value_ratio) {
    std::ostringstream msg;
    msg << "object segment " << segment.id << " of session " << segment.session
        << " is degenerate: planar (singular value ratio " << ratio
        << " < min_singular_value_ratio " << config.min_singular_value_ratio << ")";
    throw InputError(msg.str());
  }
}

/// Area-weighted vertex normals from the faces (zero for vertices of no face).
std::vector<Eigen::Vector3f> faceNormals(const Mesh& mesh) {
  std::vector<Eigen::Vector3f> normals(mesh.vertices.size(), Eigen::Vector3f::Zero());
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3f& a = mesh.vertices[static_cast<std::size_t>(t.x())];
    const Eigen::Vector3f n = (mesh.vertices[static_cast<std::size_t>(t.y())] - a)
                                  .cross(mesh.vertices[static_cast<std::size_t>(t.z())] - a);
    for (int k = 0; k < 3; ++k) normals[static_cast<std::size_t>(t[k])] += n;
  }
  return normals;
}

}  // namespace

void ObservationConfig::validate() const {
  auto fail = [](const std::string& field, const std::string& rule) {
    throw InputError("invalid observation config: " + field + " " + rule);
  };
  if (!std::isfinite(band_voxels) || band_voxels < 1.0f) fail("band_voxels", "must be >= 1");
  if (!std::isfinite(sample_spacing_voxels) || sample_spacing_voxels <= 0.0f) {
    fail("sample_spacing_voxels", "must be > 0");
  }
  if (min_samples < 4) fail("min_samples", "must be >= 4");
  if (!std::isfinite(min_singular_value_ratio) || min_singular_value_ratio < 0.0f ||
      min_singular_value_ratio >= 1.0f) {
    fail("min_singular_value_ratio", "must be in [0, 1)");
  }
}

SurfaceCloud sampleSurface(const Mesh& mesh, float spacing_m) {
  if (!std::isfinite(spacing_m) || spacing_m <= 0.0f) {
    throw InputError("sampleSurface: spacing_m must be > 0");
  }
  const std::vector<Eigen::Vector3f> from_faces = faceNormals(mesh);
  // Per cube: the vertex nearest its centre (lowest index on ties).
  std::unordered_map<CellKey, std::pair<float, std::size_t>> best;
  std::vector<std::pair<Eigen::Vector3i, std::size_t>> chosen;
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3f& p = mesh.vertices[i];
    const bool has_normal = (mesh.hasNormals() && mesh.normals[i].squaredNorm() > 1e-12f) ||
                            from_faces[i].squaredNorm() > 0.0f;
    if (!has_normal || !p.allFinite()) continue;
    const Eigen::Vector3i c = cellOf(p, spacing_m);
    const Eigen::Vector3f centre = (c.cast<float>() + Eigen::Vector3f::Constant(0.5f)) * spacing_m;
    const float d2 = (p - centre).squaredNorm();
    auto [it, inserted] = best.try_emplace(cellKey(c), d2, i);
    if (!inserted && d2 < it->second.first) it->second = {d2, i};
  }
  chosen.reserve(best.size());
  for (const auto& [key, entry] : best) chosen.emplace_back(unpackBlockKey(key), entry.second);
  std::sort(chosen.begin(), chosen.end(), [](const auto& a, const auto& b) {
    return std::make_tuple(a.first.z(), a.first.y(), a.first.x()) <
           std::make_tuple(b.first.z(), b.first.y(), b.first.x());
  });
  SurfaceCloud cloud;
  for (const auto& [cell, i] : chosen) {
    const bool mesh_normal = mesh.hasNormals() && mesh.normals[i].squaredNorm() > 1e-12f;
    cloud.points.push_back(mesh.vertices[i]);
    cloud.normals.push_back((mesh_normal ? mesh.normals[i] : from_faces[i]).normalized());
    if (mesh.hasColors()) cloud.colors.push_back(mesh.colors[i]);
  }
  return cloud;
}

Eigen::Vector3f boundingExtent(const SurfaceCloud& cloud) {
  if (cloud.empty()) return Eigen::Vector3f::Zero();
  Eigen::AlignedBox3f box;
  for (const auto& p : cloud.points) box.extend(p);
  Eigen::Vector3f extent = box.sizes();
  std::sort(extent.data(), extent.data() + 3, std::greater<float>());
  return extent;
}

Eigen::Vector3f meanColor(const SurfaceCloud& cloud) {
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  for (const auto& c : cloud.colors) sum += Eigen::Vector3f(c[0], c[1], c[2]);
  return cloud.colors.empty() ? sum
                              : Eigen::Vector3f(sum / static_cast<float>(cloud.colors.size()));
}

ObjectObservation observeObject(const TsdfMap& session_map, const change::LabelledSurface& surface,
                                const change::DiscoveredObject& segment, int session,
                                const ObservationConfig& config) {
  config.validate();
  session_map.config().validate();
  if (segment.mesh.vertices.empty()) {
    throw InputError("object segment " + std::to_string(segment.id) + " has no vertices");
  }
  const float voxel_m = session_map.config().voxel_size_m;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : segment.mesh.vertices) centroid += p.cast<double>();
  centroid /= static_cast<double>(segment.mesh.vertices.size());
  const Eigen::Vector3i offset_voxels = (centroid / voxel_m).array().round().cast<int>();
  const Eigen::Vector3f t_W_O = offset_voxels.cast<float>() * voxel_m;

  ObjectObservation observation;
  observation.session = session;
  observation.segment_id = segment.id;
  observation.T_W_O = Eigen::Isometry3d::Identity();
  observation.T_W_O.translation() = t_W_O.cast<double>();

  Mesh mesh_O = segment.mesh;
  for (auto& p : mesh_O.vertices) p -= t_W_O;
  observation.surface_O = sampleSurface(mesh_O, config.sample_spacing_voxels * voxel_m);
  refuseDegenerate(observation.surface_O, segment, config);

  observation.tsdf = TsdfMap(session_map.config());
  copyObjectBand(session_map, surface, segment.mesh, config.band_voxels * voxel_m, offset_voxels,
                 observation.tsdf);
  observation.extent_m = boundingExtent(observation.surface_O);
  observation.surface_area_m2 = meshArea(segment.mesh);
  observation.mean_color = meanColor(observation.surface_O);
  return observation;
}

}  // namespace strata::objects
