// The incremental loop's results as a JSON object for the demo's report.json.
#include "cli/report_json.h"
#include "cli/select_incremental.h"

namespace strata::apps {
namespace {

Json methodJson(const selection::MethodResult& m) {
  const selection::Confusion& c = m.confusion;
  Json j;
  j["method"] = selection::methodName(m.method);
  j["recall"] = c.recall();
  j["precision"] = c.precision();
  j["accuracy"] = c.accuracy();
  j["selected"] = m.selected;
  j["true_positive"] = c.true_positive;
  j["false_positive"] = c.false_positive;
  j["true_negative"] = c.true_negative;
  j["false_negative"] = c.false_negative;
  return j;
}

Json thresholdsJson(const selection::Thresholds& t) {
  Json j;
  j["coverage"] = t.coverage;
  j["color_change"] = t.color_change;
  j["depth_change_m"] = t.depth_change_m;
  j["surface_change"] = t.surface_change;
  j["ncc"] = t.ncc;
  j["histogram"] = t.histogram;
  return j;
}

Json agreementJson(const selection::DeviceReferenceAgreement& a) {
  Json j;
  j["samples"] = a.samples;
  j["hit_mismatches"] = a.hit_mismatches;
  j["surface_mismatches"] = a.surface_mismatches;
  j["keyframes"] = a.keyframes;
  j["decision_mismatches"] = a.decision_mismatches;
  return j;
}

Json imageUseJson(const IncrementalResult& r) {
  Json per_session = Json::array();
  for (const selection::ImageUse& use : r.images_per_session) {
    Json j;
    j["fused"] = use.fused;
    j["total"] = use.total;
    per_session.push_back(std::move(j));
  }
  Json j;
  j["fused"] = r.images.fused;
  j["total"] = r.images.total;
  j["share"] = r.images.share();
  j["per_session"] = std::move(per_session);
  return j;
}

Json freeSpaceJson(const IncrementalResult& r) {
  Json j;
  j["skipped_keyframes"] = r.free_space.views;
  j["vacated_samples"] = r.free_space.samples;
  j["shared_samples"] = r.free_space_shared_samples;
  j["pixels_of_skipped_keyframes"] = r.free_space_pixels;
  j["depth_pixels_kept"] = r.free_space.depth_pixels;
  j["arrived_samples"] = r.free_space.arrived_samples;
  j["voxel_observations"] = r.free_space.voxels;
  j["free_voxel_observations"] = r.free_space.free_voxels;
  j["integration_s"] = r.free_space_s;
  return j;
}

Json objectCountsJson(const change::ObjectCounts& o) {
  Json j;
  j["moved"] = o.moved;
  j["found"] = o.found;
  j["recall"] = o.recall();
  j["precision"] = o.precision();
  j["over_segmented"] = o.over_segmented;
  j["under_segmented"] = o.under_segmented;
  return j;
}

Json arrivalsJson(const change::ArrivalCounts& a) {
  Json j;
  j["arrivals"] = a.arrivals;
  j["found"] = a.found;
  j["recall"] = a.recall();
  return j;
}

Json matchJson(const change::ObjectMatch& m) {
  Json j;
  j["found"] = m.found;
  j["coverage"] = m.coverage;
  j["on_object"] = m.on_object;
  return j;
}

Json instancesJson(const std::vector<InstanceOutcome>& instances) {
  Json list = Json::array();
  for (const InstanceOutcome& o : instances) {
    Json j;
    j["session"] = o.session;
    j["object"] = o.object_id;
    j["name"] = o.name;
    j["arrival"] = o.arrival;
    j["complete"] = matchJson(o.complete);
    j["incremental"] = matchJson(o.incremental);
    list.push_back(std::move(j));
  }
  return list;
}

}  // namespace

std::string incrementalJson(const IncrementalResult& r) {
  Json methods = Json::array();
  for (const selection::MethodResult& m : r.methods) methods.push_back(methodJson(m));
  Json carried;
  carried["confirmed_points"] = r.carried.points;
  carried["voxels"] = r.carried.voxels;
  const selection::Confusion& f = r.fused_confusion;
  Json fused;
  fused["recall"] = f.recall();
  fused["precision"] = f.precision();
  fused["accuracy"] = f.accuracy();
  Json coverage;
  coverage["complete"] = r.coverage_complete;
  coverage["incremental"] = r.coverage_incremental;
  Json j;
  j["thresholds"] = thresholdsJson(r.thresholds);
  j["methods"] = std::move(methods);
  j["device_vs_reference"] = agreementJson(r.agreement);
  j["keyframes_after_first_session"] = imageUseJson(r);
  j["carried_forward"] = std::move(carried);
  j["free_space"] = freeSpaceJson(r);
  j["fused_vs_truth"] = std::move(fused);
  j["surface_coverage"] = std::move(coverage);
  j["objects_complete"] = objectCountsJson(r.objects_complete);
  j["objects_incremental"] = objectCountsJson(r.objects_incremental);
  j["arrivals_complete"] = arrivalsJson(r.arrivals_complete);
  j["arrivals_incremental"] = arrivalsJson(r.arrivals_incremental);
  j["instances"] = instancesJson(r.instances);
  j["wall_s"] = r.wall_s;
  return jsonText(j);
}

}  // namespace strata::apps
