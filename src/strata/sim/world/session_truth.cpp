#include "strata/sim/world/session_truth.h"

namespace strata::sim {

const char* changeName(Change change) {
  switch (change) {
    case Change::kNone:
      return "none";
    case Change::kMoved:
      return "moved";
    case Change::kRemoved:
      return "removed";
    case Change::kAdded:
      return "added";
  }
  return "none";
}

std::vector<int> SessionTruth::changedIds(bool since_first) const {
  std::vector<int> ids;
  for (const ObjectState& object : objects) {
    if ((since_first ? object.since_first : object.since_previous) != Change::kNone) {
      ids.push_back(object.id);
    }
  }
  return ids;
}

int SessionTruth::presentCount() const {
  int count = 0;
  for (const ObjectState& object : objects) count += object.present ? 1 : 0;
  return count;
}

}  // namespace strata::sim
