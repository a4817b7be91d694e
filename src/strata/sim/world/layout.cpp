#include "strata/sim/world/internal/layout.h"

#include <algorithm>

#include "strata/core/error.h"
#include "strata/sim/world/internal/placer.h"

namespace strata::sim {
namespace {

const ObjectSpec& objectSpec(const WorldSpec& spec, int index) {
  const int n = static_cast<int>(spec.objects.size());
  return index < n ? spec.objects[index] : spec.pool[index - n];
}

[[noreturn]] void failAt(const WorldSpec& spec, int index, const std::string& what) {
  const ObjectSpec& object = objectSpec(spec, index);
  throw InputError(spec.source + ":" + std::to_string(object.line) + ": object '" + object.name +
                   "': " + what);
}

const ChangeRules& rulesFor(const WorldSpec& spec, int session) {
  for (const SessionOverride& entry : spec.overrides) {
    if (entry.session == session) return entry.rules;
  }
  return spec.changes;
}

/// Session 0: given poses first (checked), then the others drawn from the seed.
Layout initialLayout(const LayoutInput& input, Placer& placer) {
  const WorldSpec& spec = *input.spec;
  Layout layout(input.half_footprints_m.size());
  for (std::size_t i = 0; i < spec.objects.size(); ++i) {
    const ObjectSpec& object = spec.objects[i];
    if (!object.at_m) continue;
    const std::string hit = placer.conflict(static_cast<int>(i), *object.at_m, object.yaw_deg, 0.0);
    if (!hit.empty()) failAt(spec, static_cast<int>(i), "its given pose overlaps " + hit);
    layout[i] = Placement{true, *object.at_m, object.yaw_deg};
    placer.set(static_cast<int>(i), layout[i]);
  }
  Rng rng(hashCombine(spec.seed, 0));
  for (std::size_t i = 0; i < spec.objects.size(); ++i) {
    if (spec.objects[i].at_m) continue;
    const std::optional<Placement> placed = placer.sample(static_cast<int>(i), rng, nullptr, 0.0);
    if (!placed) failAt(spec, static_cast<int>(i), "no free place in the placement regions");
    layout[i] = *placed;
    placer.set(static_cast<int>(i), layout[i]);
  }
  return layout;
}

/// One later session: draws, then applies, the changes; returns how many took place.
class SessionStep {
 public:
  SessionStep(const LayoutInput& input, const Layout& previous, int session)
      : rules_(rulesFor(*input.spec, session)),
        placer_(input),
        next_(previous),
        rng_(hashCombine(input.spec->seed, static_cast<std::uint64_t>(session))),
        changed_(previous.size(), false) {
    for (std::size_t i = 0; i < next_.size(); ++i) placer_.set(static_cast<int>(i), next_[i]);
  }

  Layout run() {
    std::vector<int> to_move, to_remove;
    for (int i = 0; i < static_cast<int>(next_.size()); ++i) {
      if (!next_[i].present) continue;
      const double u = rng_.uniform();
      if (u < rules_.remove_probability)
        to_remove.push_back(i);
      else if (u < rules_.remove_probability + rules_.move_probability)
        to_move.push_back(i);
    }
    const std::vector<int> to_add = drawAdditions();
    for (const int i : to_remove) remove(i);
    for (const int i : to_move) tryMove(i);
    for (const int i : to_add) tryAdd(i);
    forceMinimumChanges();
    return next_;
  }

  int changes() const { return changes_; }

 private:
  std::vector<int> drawAdditions() {
    std::vector<int> absent;
    for (int i = 0; i < static_cast<int>(next_.size()); ++i) {
      if (!next_[i].present) absent.push_back(i);
    }
    const int count =
        std::min(rng_.uniformInt(rules_.add_min, rules_.add_max), static_cast<int>(absent.size()));
    for (int k = 0; k < count; ++k) {  // partial Fisher-Yates: the first `count` are the draw
      std::swap(absent[k], absent[rng_.uniformInt(k, static_cast<int>(absent.size()) - 1)]);
    }
    absent.resize(count);
    return absent;
  }

  void remove(int i) {
    next_[i].present = false;
    placer_.set(i, next_[i]);
    mark(i);
  }

  bool tryMove(int i) {
    const Placement old = next_[i];
    placer_.set(i, Placement{});  // its own old spot does not block it
    const std::optional<Placement> moved =
        placer_.sample(i, rng_, &old, rules_.min_move_distance_m);
    next_[i] = moved ? *moved : old;
    placer_.set(i, next_[i]);
    if (moved) mark(i);
    return moved.has_value();
  }

  bool tryAdd(int i) {
    const std::optional<Placement> placed = placer_.sample(i, rng_, nullptr, 0.0);
    if (!placed) return false;
    next_[i] = *placed;
    placer_.set(i, next_[i]);
    mark(i);
    return true;
  }

  /// Tops the session up to min_changes: move (or else remove) an unchanged present object, or add
  /// an absent one when nothing is present.
  void forceMinimumChanges() {
    while (changes_ < rules_.min_changes) {
      std::vector<int> present, absent;
      for (int i = 0; i < static_cast<int>(next_.size()); ++i) {
        if (changed_[i]) continue;
        (next_[i].present ? present : absent).push_back(i);
      }
      if (!present.empty()) {
        const int i = present[rng_.uniformInt(0, static_cast<int>(present.size()) - 1)];
        if (!tryMove(i)) remove(i);
      } else if (absent.empty() ||
                 !tryAdd(absent[rng_.uniformInt(0, static_cast<int>(absent.size()) - 1)])) {
        return;  // nothing left to change: the caller reports it
      }
    }
  }

  void mark(int i) {
    if (!changed_[i]) ++changes_;
    changed_[i] = true;
  }

  const ChangeRules& rules_;
  Placer placer_;
  Layout next_;
  Rng rng_;
  std::vector<bool> changed_;
  int changes_ = 0;
};

}  // namespace

std::vector<Layout> generateLayouts(const LayoutInput& input) {
  const WorldSpec& spec = *input.spec;
  Placer placer(input);
  std::vector<Layout> layouts = {initialLayout(input, placer)};
  for (int session = 1; session < spec.session_count; ++session) {
    SessionStep step(input, layouts.back(), session);
    layouts.push_back(step.run());
    if (step.changes() == 0) {
      throw InputError(spec.source + ": session " + std::to_string(session) +
                       ": no object could be moved, removed or added (too little free space?)");
    }
  }
  return layouts;
}

}  // namespace strata::sim
