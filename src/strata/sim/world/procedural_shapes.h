#pragma once
// Procedural shapes for the simulator's worlds: irregular objects that boxes, cylinders and the
// simple furniture do not cover, each generated deterministically from its spec (size and seed).
// Every shape is given in its own frame (footprint centred on the origin, bottom at z = 0, +z up)
// and fills its `size_m` bounding box exactly; parts are closed meshes with outward normals whose
// interiors are disjoint (they may touch), like shape_mesh.h's.
//
//  - vase (ShapeKind::kVase): a solid of revolution, radius along the height from a few seeded
//    sinusoids (belly, neck, foot); its yaw symmetry is total for a round footprint.
//  - blob: a star-shaped lump (a sphere whose radius is deformed by seeded smooth noise), its
//    bottom flattened so it stands on the floor; no symmetry.
//  - tube: a bent tube, a circle swept along a seeded curve that winds 180-270 degrees about the
//    vertical and rises in between; it touches the floor at its two ends.
//  - l_shape, u_shape: two or three boxes joined in an L or U footprint, `thickness_m` thick arms.
//  - stool: a round (elliptic for x != y) seat on `legs` thin round legs.
//
// Pure functions of their arguments, thread safe. The same seed gives the same vertices bit for
// bit on one platform (std::sin/std::cos from libm; other libms may differ in the last bit).
#include <vector>

#include "strata/mesh/mesh.h"
#include "strata/sim/world/world_spec.h"

namespace strata::sim {

/// True for the kinds generated from a seed (vase, blob, tube): World mixes its seed into theirs.
bool isProceduralSeeded(ShapeKind kind);

/// True for the kinds of this header (vase .. stool).
bool isProcedural(ShapeKind kind);

/// The closed parts of a procedural shape. InputError for a kind that is not procedural, a
/// non-positive size, a thickness that does not fit the footprint or legs outside [3, 8].
std::vector<Mesh> proceduralParts(const ShapeSpec& shape);

/// Yaw symmetry order of a procedural shape as the evaluation counts it: 0 for any yaw (a round
/// vase), n for n-fold (a round stool of n legs, an elliptic vase 2), 1 for none.
int proceduralYawSymmetry(const ShapeSpec& shape);

/// Signed volume of a triangle mesh (positive for a closed mesh with outward normals), m^3.
double signedVolume(const Mesh& mesh);

}  // namespace strata::sim
