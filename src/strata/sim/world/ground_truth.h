#pragma once
// Ground truth of a world on disk, for evaluation and for people to look at. Layout under `dir`:
//   static.ply                          rooms and static furniture, world frame
//   objects/<id>_<name>.ply             every movable object in its own frame
//   session_<k>/world.ply               static + present objects, world frame
//   session_<k>/objects/<id>_<name>.ply each present object in the world frame
//   session_<k>/objects.json            ids, names, shapes, poses, presence, change labels, light
// PLY: binary little-endian with per-vertex albedo colours. Every file is written atomically, and
// the same world and seed give byte-identical files.
#include <string>

#include "strata/sim/world/world.h"

namespace strata::sim {

/// Writes the whole layout above, creating folders. Error naming the path on failure.
void writeGroundTruth(const World& world, const std::string& dir);

/// Writes one session's folder content (world.ply, objects/, objects.json) directly into `dir`.
void writeSessionGroundTruth(const World& world, int session, const std::string& dir);

/// objects.json of one session (format in worlds/README.md).
std::string sessionJson(const World& world, int session);

/// "<id>_<name>" with a two-digit id: file stem of an object's meshes.
std::string objectFileStem(const World& world, int object_id);

}  // namespace strata::sim
