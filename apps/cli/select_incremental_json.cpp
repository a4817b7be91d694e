// The incremental loop's results as a JSON object for the demo's report.json.
#include <sstream>

#include "cli/select_incremental.h"
#include "core/json_text.h"

namespace strata::apps {
namespace {

void writeConfusion(std::ostringstream& out, const selection::MethodResult& m) {
  const selection::Confusion& c = m.confusion;
  out << "{\"method\": " << jsonQuoted(selection::methodName(m.method))
      << ", \"recall\": " << c.recall() << ", \"precision\": " << c.precision()
      << ", \"accuracy\": " << c.accuracy() << ", \"selected\": " << m.selected
      << ", \"true_positive\": " << c.true_positive << ", \"false_positive\": " << c.false_positive
      << ", \"true_negative\": " << c.true_negative << ", \"false_negative\": " << c.false_negative
      << "}";
}

void writeObjects(std::ostringstream& out, const change::ObjectCounts& o) {
  out << "{\"moved\": " << o.moved << ", \"found\": " << o.found << ", \"recall\": " << o.recall()
      << ", \"precision\": " << o.precision() << ", \"over_segmented\": " << o.over_segmented
      << ", \"under_segmented\": " << o.under_segmented << "}";
}

void writeArrivals(std::ostringstream& out, const change::ArrivalCounts& a) {
  out << "{\"arrivals\": " << a.arrivals << ", \"found\": " << a.found
      << ", \"recall\": " << a.recall() << "}";
}

void writeMatch(std::ostringstream& out, const change::ObjectMatch& m) {
  out << "{\"found\": " << (m.found ? "true" : "false") << ", \"coverage\": " << m.coverage
      << ", \"on_object\": " << m.on_object << "}";
}

void writeInstances(std::ostringstream& out, const std::vector<InstanceOutcome>& instances) {
  out << "[";
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const InstanceOutcome& o = instances[i];
    out << (i > 0 ? ", " : "") << "{\"session\": " << o.session << ", \"object\": " << o.object_id
        << ", \"name\": " << jsonQuoted(o.name)
        << ", \"arrival\": " << (o.arrival ? "true" : "false") << ", \"complete\": ";
    writeMatch(out, o.complete);
    out << ", \"incremental\": ";
    writeMatch(out, o.incremental);
    out << "}";
  }
  out << "]";
}

}  // namespace

std::string incrementalJson(const IncrementalResult& r) {
  std::ostringstream out;
  out.precision(6);
  const selection::Thresholds& t = r.thresholds;
  out << "{\"thresholds\": {\"coverage\": " << t.coverage
      << ", \"color_change\": " << t.color_change << ", \"depth_change_m\": " << t.depth_change_m
      << ", \"surface_change\": " << t.surface_change << ", \"ncc\": " << t.ncc
      << ", \"histogram\": " << t.histogram << "}, \"methods\": [";
  for (std::size_t i = 0; i < r.methods.size(); ++i) {
    if (i > 0) out << ", ";
    writeConfusion(out, r.methods[i]);
  }
  out << "], \"device_vs_reference\": {\"samples\": " << r.agreement.samples
      << ", \"hit_mismatches\": " << r.agreement.hit_mismatches
      << ", \"surface_mismatches\": " << r.agreement.surface_mismatches
      << ", \"keyframes\": " << r.agreement.keyframes
      << ", \"decision_mismatches\": " << r.agreement.decision_mismatches
      << "}, \"keyframes_after_first_session\": {\"fused\": " << r.images.fused
      << ", \"total\": " << r.images.total << ", \"share\": " << r.images.share()
      << ", \"per_session\": [";
  for (std::size_t i = 0; i < r.images_per_session.size(); ++i) {
    const selection::ImageUse& use = r.images_per_session[i];
    out << (i > 0 ? ", " : "") << "{\"fused\": " << use.fused << ", \"total\": " << use.total
        << "}";
  }
  out << "]}, \"carried_forward\": {\"confirmed_points\": " << r.carried.points
      << ", \"voxels\": " << r.carried.voxels
      << "}, \"free_space\": {\"skipped_keyframes\": " << r.free_space.views
      << ", \"vacated_samples\": " << r.free_space.samples
      << ", \"shared_samples\": " << r.free_space_shared_samples
      << ", \"pixels_of_skipped_keyframes\": " << r.free_space_pixels
      << ", \"depth_pixels_kept\": " << r.free_space.depth_pixels
      << ", \"arrived_samples\": " << r.free_space.arrived_samples
      << ", \"voxel_observations\": " << r.free_space.voxels
      << ", \"free_voxel_observations\": " << r.free_space.free_voxels
      << ", \"integration_s\": " << r.free_space_s << "}, \"fused_vs_truth\": ";
  const selection::Confusion& f = r.fused_confusion;
  out << "{\"recall\": " << f.recall() << ", \"precision\": " << f.precision()
      << ", \"accuracy\": " << f.accuracy()
      << "}, \"surface_coverage\": {\"complete\": " << r.coverage_complete
      << ", \"incremental\": " << r.coverage_incremental << "}, \"objects_complete\": ";
  writeObjects(out, r.objects_complete);
  out << ", \"objects_incremental\": ";
  writeObjects(out, r.objects_incremental);
  out << ", \"arrivals_complete\": ";
  writeArrivals(out, r.arrivals_complete);
  out << ", \"arrivals_incremental\": ";
  writeArrivals(out, r.arrivals_incremental);
  out << ", \"instances\": ";
  writeInstances(out, r.instances);
  out << ", \"wall_s\": " << r.wall_s << "}";
  return out.str();
}

}  // namespace strata::apps
