// Matching discovered segments to the objects that moved (definitions in evaluation.h).
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <sstream>

#include "strata/change/eval/evaluation.h"
#include "strata/change/eval/internal/evaluation_surface_index.h"
#include "strata/core/error.h"

namespace strata::change {
namespace {

/// Area of the segment's faces on each truth object (by id), as shares of the segment's area:
/// every face counts for the nearest object within the match distance of its centroid.
std::map<int, double> areaShares(const Mesh& segment, const SurfaceIndex& truth, float distance_m) {
  std::map<int, double> area;
  double total = 0.0;
  for (const Eigen::Vector3i& t : segment.triangles) {
    const Eigen::Vector3f& a = segment.vertices[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3f& b = segment.vertices[static_cast<std::size_t>(t[1])];
    const Eigen::Vector3f& c = segment.vertices[static_cast<std::size_t>(t[2])];
    const double face_area = 0.5 * static_cast<double>((b - a).cross(c - a).norm());
    total += face_area;
    SurfaceIndex::Hit hit;
    if (truth.nearest((a + b + c) / 3.0f, distance_m, hit)) area[hit.tag] += face_area;
  }
  if (total > 0.0) {
    for (auto& [id, value] : area) value /= total;
  }
  return area;
}

SegmentMatch matchSegment(const DiscoveredObject& segment, const std::map<int, double>& shares,
                          const std::vector<TruthObject>& truth, const EvaluationConfig& config) {
  SegmentMatch match;
  match.segment_id = segment.id;
  match.vertices = segment.vertex_count;
  int objects_touched = 0;
  for (const TruthObject& object : truth) {
    const auto it = shares.find(object.id);
    const double share = it == shares.end() ? 0.0 : it->second;
    if (share >= config.under_segment_min_share) ++objects_touched;
    if (object.moved && share >= config.segment_min_on_object && share > match.on_object) {
      match.object_id = object.id;
      match.on_object = share;
    }
  }
  match.under_segmented = objects_touched >= 2;
  return match;
}

bool boxesNear(const Eigen::AlignedBox3f& a, const Eigen::AlignedBox3f& b, float margin) {
  Eigen::AlignedBox3f grown = a;
  grown.min().array() -= margin;
  grown.max().array() += margin;
  return grown.intersects(b);
}

ObjectMatch matchObject(const TruthObject& object, const std::vector<DiscoveredObject>& segments,
                        const std::vector<std::unique_ptr<SurfaceIndex>>& segment_surfaces,
                        const std::vector<std::map<int, double>>& shares,
                        const EvaluationConfig& config) {
  ObjectMatch match;
  match.object_id = object.id;
  match.name = object.name;
  match.visible_area_m2 = object.visible_area_m2;
  match.evaluated = object.visible_area_m2 >= config.min_visible_area_m2;
  Eigen::AlignedBox3f seen;
  for (const Eigen::Vector3f& p : object.visible_points) seen.extend(p);
  for (std::size_t s = 0; s < segments.size(); ++s) {
    if (seen.isEmpty() || !boxesNear(segments[s].bbox, seen, config.match_distance_m)) continue;
    const double coverage =
        shareWithin(object.visible_points, *segment_surfaces[s], config.match_distance_m);
    const auto it = shares[s].find(object.id);
    const double on = it == shares[s].end() ? 0.0 : it->second;
    const bool found = coverage >= config.found_min_coverage && on >= config.found_min_on_object;
    // Prefer a segment that finds the object, then the one covering most of it.
    if ((found && !match.found) || (found == match.found && coverage > match.coverage)) {
      match.found = found;
      match.best_segment = segments[s].id;
      match.coverage = coverage;
      match.on_object = on;
    }
  }
  return match;
}

}  // namespace

ObjectCounts& ObjectCounts::operator+=(const ObjectCounts& o) {
  moved += o.moved;
  found += o.found;
  segments += o.segments;
  true_segments += o.true_segments;
  false_positives += o.false_positives;
  over_segmented += o.over_segmented;
  under_segmented += o.under_segmented;
  return *this;
}

SessionObjectEvaluation evaluateObjects(int session, const std::vector<TruthObject>& truth,
                                        const std::vector<DiscoveredObject>& segments,
                                        const EvaluationConfig& config) {
  config.validate();
  SessionObjectEvaluation result;
  result.session = session;
  SurfaceIndex truth_surface(config.match_distance_m);
  for (const TruthObject& object : truth) truth_surface.add(object.mesh, object.id);
  std::vector<std::map<int, double>> shares;
  std::vector<std::unique_ptr<SurfaceIndex>> segment_surfaces;
  for (const DiscoveredObject& segment : segments) {
    shares.push_back(areaShares(segment.mesh, truth_surface, config.match_distance_m));
    segment_surfaces.push_back(std::make_unique<SurfaceIndex>(config.match_distance_m));
    segment_surfaces.back()->add(segment.mesh);
    result.segments.push_back(matchSegment(segment, shares.back(), truth, config));
  }
  for (const TruthObject& object : truth) {
    if (!object.moved) continue;
    ObjectMatch match = matchObject(object, segments, segment_surfaces, shares, config);
    match.segments = static_cast<int>(
        std::count_if(result.segments.begin(), result.segments.end(),
                      [&](const SegmentMatch& s) { return s.object_id == object.id; }));
    result.objects.push_back(match);
  }
  ObjectCounts& c = result.counts;
  for (const ObjectMatch& m : result.objects) {
    if (!m.evaluated) continue;
    ++c.moved;
    if (m.found) ++c.found;
    if (m.segments >= 2) ++c.over_segmented;
  }
  for (const SegmentMatch& s : result.segments) {
    ++c.segments;
    if (s.object_id != 0) ++c.true_segments;
    if (s.under_segmented) ++c.under_segmented;
  }
  c.false_positives = c.segments - c.true_segments;
  return result;
}

std::string describeCounts(const ObjectCounts& c) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(1);
  out << "precision " << 100.0 * c.precision() << " % (" << c.true_segments << "/" << c.segments
      << " segments), recall " << 100.0 * c.recall() << " % (" << c.found << "/" << c.moved
      << " moved objects), over-segmented " << c.over_segmented << ", under-segmented "
      << c.under_segmented;
  return out.str();
}

}  // namespace strata::change
