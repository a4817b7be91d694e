#pragma once
// Scores of a keyframe selection against the ground truth (selection_truth.h).
#include <cstdint>
#include <string>
#include <vector>

#include "strata/select/eval/selection_truth.h"

namespace strata::selection {

struct Confusion {
  int true_positive = 0;
  int false_positive = 0;
  int true_negative = 0;
  int false_negative = 0;

  int total() const { return true_positive + false_positive + true_negative + false_negative; }
  /// Shares in [0, 1]; recall/precision are 1 when nothing was there to find / nothing selected.
  double recall() const;
  double precision() const;
  double accuracy() const;
  void add(bool selected, bool positive);
  void add(const Confusion& other);
  /// "recall 87.1 %, precision 93.0 %, accuracy 90.2 % (TP 61, FP 4, TN 50, FN 9)".
  std::string describe() const;
};

Confusion confusion(const std::vector<std::uint8_t>& selected,
                    const std::vector<KeyframeTruth>& truth);

}  // namespace strata::selection
