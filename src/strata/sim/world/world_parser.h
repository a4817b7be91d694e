#pragma once
// World files (YAML). Units: metres, degrees (yaw), albedo as 0-255 integers. z is up, every floor
// is at z = 0, yaw turns counter-clockwise about +z seen from above. Full reference with examples:
// worlds/README.md. Shape of a file:
//
//   name: room                  # text; default: the file name
//   seed: 7                     # layout seed (non-negative integer)
//   sessions: 5                 # session count >= 1
//   wall_thickness: 0.1         # m, walls, floor and ceiling slabs
//   rooms:                      # >= 1; interior floor rectangle [min, max], walls outside it
//     - {name: main, min: [0, 0], max: [5, 4], height: 2.5,
//        floor: {albedo: [150, 140, 120]}, walls: {...}, ceiling: {...}}
//   doors:                      # an opening in every wall through `at`
//     - {at: [5.05, 2.0], width: 0.9, height: 2.0}
//   static:                     # fixed furniture: box, cylinder, pillar, chair, table, shelf, mesh
//     - {name: pillar_a, type: pillar, radius: 0.15, at: [4, 1]}
//   objects:                    # movable, present in session 0 (`at` absent: placed by the seed)
//     - {name: crate_a, type: box, size: [0.5, 0.4, 0.3], albedo: [200, 60, 40], at: [1, 1],
//        yaw: 15, reflectivity: 0.0}
//     - {name: bunny, type: mesh, file: data:meshes/stanford-bunny.obj, scale: 1.5, up: y,
//        optional: true}
//   pool:                       # movable, absent in session 0, may be added later (same keys)
//   placement: {regions: [{min: [0.3, 0.3], max: [4.7, 3.7]}], clearance: 0.1, door_clearance: 0.6}
//   changes: {move_probability: 0.25, remove_probability: 0.1, add: [0, 1], min_changes: 1,
//             min_move_distance: 0.3, sessions: [{session: 3, move_probability: 0.6}]}
//   lighting: {direction: [0.3, -0.4, 1], intensity: 0.65, ambient: 0.35,   # direction: to the
//   light
//              vary_direction: 15, vary_intensity: 0.2}
//
// Every error is an InputError "file:line: field.path: what is wrong", e.g.
//   room.yaml:12: objects[3].size: expected 3 numbers, got 2
// Unknown keys are errors (with a suggestion for typos), so a misspelt key never silently falls
// back to a default.
#include <string>

#include "strata/sim/world/world_spec.h"

namespace strata::sim {

/// Parses and validates a world file's text. `name_for_errors` prefixes messages; relative mesh
/// paths resolve against `base_dir`. Mesh files are checked to exist (an `optional: true` object
/// whose file is missing is dropped with a warning on stderr), not yet read.
WorldSpec parseWorldSpec(const std::string& text, const std::string& name_for_errors,
                         const std::string& base_dir);

}  // namespace strata::sim
