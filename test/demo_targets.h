#pragma once
// The demo's targets on the shipped room, shared by the CI runs (fewer sessions or frames, in
// test_change_demo and test_objects_demo) and the full runs labelled long (test_demo_long).
#include <cstddef>
#include <string>

#include "cli/demo_command.h"
#include "cli/demo_report.h"

namespace strata::test {

/// Demo options on the shipped room with the demo's settings and a fresh output folder `name`.
apps::DemoOptions roomDemoOptions(const std::string& name);

/// roomDemoOptions for `strata demo --vio` without the object database: two sessions of `frames`
/// RGB-D frames each, fused on poses from stereo VIO over 376 x 240 grey stereo.
apps::DemoOptions roomVioDemoOptions(const std::string& name, int frames);

/// Change detection and keyframe selection (--incremental) against the truth: precision >= 99 %,
/// recall >= 95 % of at least `min_moved` moved objects, >= 98 % of the static surface within
/// 2 cm, <= 1 % of the static mesh on moved objects; the selected keyframes keep >= 98 % of the
/// complete map's coverage and find the moved objects (>= `min_arrivals` arrivals) the complete
/// run finds, within one; the report's incremental block is complete and self-consistent.
void expectRoomChangeTargets(const apps::DemoReport& report, std::size_t min_moved,
                             std::size_t min_arrivals);

/// The demo on VIO poses: every session's `frames` RGB-D frames fused on VIO poses but the few
/// before tracking starts (<= 3 skipped), pose error 1-50 mm RMSE, < 100 mm at most, < 2 deg;
/// change detection recall >= 85 %, precision >= 75 % of at least `min_moved` moved objects.
void expectVioDemoTargets(const apps::DemoReport& report, std::size_t sessions, std::size_t frames,
                          std::size_t min_moved);

/// The object database step: pair precision >= 99 % over at least `min_same_object` pairs,
/// recall and main-segment recall at least `min_recall` / `min_main_recall`, pose median <= 1 cm
/// and <= 2 deg, no model grown over 2x, and its files in the demo's output folder.
void expectRoomObjectTargets(const apps::DemoReport& report, const std::string& out_dir,
                             std::size_t min_same_object, double min_recall,
                             double min_main_recall);

}  // namespace strata::test
