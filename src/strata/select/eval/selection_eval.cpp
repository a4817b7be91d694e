#include "strata/select/eval/selection_eval.h"

#include <cstdio>

#include "strata/core/error.h"

namespace strata::selection {

double Confusion::recall() const {
  const int positives = true_positive + false_negative;
  return positives > 0 ? static_cast<double>(true_positive) / positives : 1.0;
}

double Confusion::precision() const {
  const int selected = true_positive + false_positive;
  return selected > 0 ? static_cast<double>(true_positive) / selected : 1.0;
}

double Confusion::accuracy() const {
  return total() > 0 ? static_cast<double>(true_positive + true_negative) / total() : 1.0;
}

void Confusion::add(bool selected, bool positive) {
  if (selected && positive) ++true_positive;
  if (selected && !positive) ++false_positive;
  if (!selected && !positive) ++true_negative;
  if (!selected && positive) ++false_negative;
}

void Confusion::add(const Confusion& o) {
  true_positive += o.true_positive;
  false_positive += o.false_positive;
  true_negative += o.true_negative;
  false_negative += o.false_negative;
}

std::string Confusion::describe() const {
  char text[160];
  std::snprintf(text, sizeof(text),
                "recall %.1f %%, precision %.1f %%, accuracy %.1f %% (TP %d, FP %d, TN %d, FN %d)",
                100.0 * recall(), 100.0 * precision(), 100.0 * accuracy(), true_positive,
                false_positive, true_negative, false_negative);
  return text;
}

Confusion confusion(const std::vector<std::uint8_t>& selected,
                    const std::vector<KeyframeTruth>& truth) {
  if (selected.size() != truth.size()) {
    throw InputError("confusion: " + std::to_string(selected.size()) + " decisions but " +
                     std::to_string(truth.size()) + " truths");
  }
  Confusion c;
  for (std::size_t i = 0; i < truth.size(); ++i) c.add(selected[i] != 0, truth[i].positive);
  return c;
}

}  // namespace strata::selection
