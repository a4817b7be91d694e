#pragma once
// Files of a change-detection run (`strata diff`, `strata demo`): the static mesh, one PLY per
// discovered object per session, and a label overlay PNG per session.
#include <string>
#include <vector>

#include "strata/mapper/session_diff.h"

namespace strata::apps {

struct DiffFiles {
  std::string static_mesh;                              // static_mesh.ply
  std::vector<std::vector<std::string>> object_meshes;  // [session][object]: session_S_object_K.ply
  std::vector<std::string> overlays;                    // session_S_overlay.png ("" when empty)
};

/// Writes everything into `out_dir` (which must exist); paths in the result are as written.
/// Throws Error naming a file that cannot be written.
DiffFiles writeDiffFiles(const DiffResult& result, const std::string& out_dir);

}  // namespace strata::apps
