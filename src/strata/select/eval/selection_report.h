#pragma once
// Results of a SelectionLoop run with its LoopTruth: every method's confusion against the ground truth
// (all methods decide from the same scores, each with its automatic threshold), and how well the
// device and the host reference agree.
#include <string>
#include <vector>

#include "strata/select/eval/selection_eval.h"
#include "strata/select/eval/selection_loop_truth.h"

namespace strata::selection {

struct MethodResult {
  Method method = Method::kReprojection;
  Confusion confusion;  // keyframes of sessions >= 1
  std::size_t selected = 0;
};

/// `truth`: recorded while `loop` ran. Methods in the order reprojection, ncc, hist.
std::vector<MethodResult> evaluateMethods(const SelectionLoop& loop, const LoopTruth& truth);

struct DeviceReferenceAgreement {
  std::size_t samples = 0;
  std::size_t hit_mismatches = 0;       // samples whose hit differs
  std::size_t surface_mismatches = 0;   // samples whose surface check differs
  std::size_t keyframes = 0;            // sessions >= 1
  std::size_t decision_mismatches = 0;  // per method: keyframes decided differently, summed
  double hitAgreement() const;
  double surfaceAgreement() const;
};

/// Needs a loop run with_reference: the reference path decides with its own scores and its own
/// automatic thresholds, every method.
DeviceReferenceAgreement deviceReferenceAgreement(const SelectionLoop& loop);

/// Keyframes of sessions >= 1: fused / all.
struct ImageUse {
  std::size_t fused = 0;
  std::size_t total = 0;
  double share() const { return total > 0 ? static_cast<double>(fused) / total : 0.0; }
};
ImageUse imagesAfterFirstSession(const SelectionLoop& loop);
/// The same per session, sessions >= 1 in order: the share falls as the map fills.
std::vector<ImageUse> imagesPerSession(const SelectionLoop& loop);

/// A fixed-width table: method, recall, precision, accuracy, selected.
std::string formatMethodTable(const std::vector<MethodResult>& results);

}  // namespace strata::selection
