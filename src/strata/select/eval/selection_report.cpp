#include "strata/select/eval/selection_report.h"

#include <cstdio>

namespace strata::selection {
namespace {

constexpr Method kMethods[] = {Method::kReprojection, Method::kNcc, Method::kHistogram};

std::vector<std::uint8_t> decide(const std::vector<KeyframeScore>& scores,
                                 const SelectionConfig& base, Method method,
                                 const Thresholds& thresholds) {
  SelectionConfig config = base;
  config.method = method;
  config.thresholds = thresholds;
  return selectKeyframes(scores, config).selected;
}

}  // namespace

std::vector<MethodResult> evaluateMethods(const SelectionLoop& loop, const LoopTruth& truth) {
  std::vector<MethodResult> out;
  for (Method method : kMethods) {
    MethodResult r;
    r.method = method;
    for (const SessionRun& run : loop.sessions()) {
      if (run.session == 0) continue;
      const auto selected = decide(run.scores, loop.config().selection, method, loop.thresholds());
      r.confusion.add(confusion(selected, truth.truth(run.session)));
      for (auto s : selected) r.selected += s;
    }
    out.push_back(r);
  }
  return out;
}

double DeviceReferenceAgreement::hitAgreement() const {
  return samples > 0 ? 1.0 - static_cast<double>(hit_mismatches) / samples : 1.0;
}

double DeviceReferenceAgreement::surfaceAgreement() const {
  return samples > 0 ? 1.0 - static_cast<double>(surface_mismatches) / samples : 1.0;
}

DeviceReferenceAgreement deviceReferenceAgreement(const SelectionLoop& loop) {
  DeviceReferenceAgreement a;
  for (const SessionRun& run : loop.sessions()) {
    for (std::size_t k = 0; k < run.device_samples.size(); ++k) {
      const auto& device = run.device_samples[k].hit;
      const auto& reference = run.reference_samples[k].hit;
      a.samples += device.size();
      for (std::size_t i = 0; i < device.size(); ++i) a.hit_mismatches += device[i] != reference[i];
      const auto& device_surface = run.device_samples[k].surface;
      const auto& reference_surface = run.reference_samples[k].surface;
      for (std::size_t i = 0; i < device_surface.size(); ++i) {
        a.surface_mismatches += device_surface[i] != reference_surface.at(i);
      }
    }
    if (run.session == 0) continue;
    a.keyframes += run.scores.size();
    for (Method method : kMethods) {
      const auto device = decide(run.scores, loop.config().selection, method, loop.thresholds());
      const auto reference =
          decide(run.reference_scores, loop.config().selection, method, loop.referenceThresholds());
      for (std::size_t i = 0; i < device.size(); ++i)
        a.decision_mismatches += device[i] != reference[i];
    }
  }
  return a;
}

std::vector<ImageUse> imagesPerSession(const SelectionLoop& loop) {
  std::vector<ImageUse> out;
  for (const SessionRun& run : loop.sessions()) {
    if (run.session == 0) continue;
    out.push_back({run.fusedCount(), run.fused.size()});
  }
  return out;
}

ImageUse imagesAfterFirstSession(const SelectionLoop& loop) {
  ImageUse use;
  for (const ImageUse& session : imagesPerSession(loop)) {
    use.fused += session.fused;
    use.total += session.total;
  }
  return use;
}

std::string formatMethodTable(const std::vector<MethodResult>& results) {
  std::string out = "method  recall  precision  accuracy  selected   TP  FP  TN  FN\n";
  for (const MethodResult& r : results) {
    const Confusion& c = r.confusion;
    char line[160];
    std::snprintf(line, sizeof(line), "%-6s  %5.1f%%  %8.1f%%  %7.1f%%  %8zu  %3d %3d %3d %3d\n",
                  methodName(r.method), 100.0 * c.recall(), 100.0 * c.precision(),
                  100.0 * c.accuracy(), r.selected, c.true_positive, c.false_positive,
                  c.true_negative, c.false_negative);
    out += line;
  }
  return out;
}

}  // namespace strata::selection
