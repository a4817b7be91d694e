#pragma once
// The label overlay of `strata diff` / `strata demo`: a session's surface seen from above
// (orthographic along -z, world z up), shaded grey, with each discovered object in its own colour,
// a legend naming them, a 1 m scale bar and a title line.
#include <string>
#include <vector>

#include "strata/change/object_discovery.h"
#include "strata/core/types.h"
#include "strata/mesh/mesh.h"

namespace strata::apps {

struct OverlayOptions {
  /// The picture's map part is at most this many pixels on its longer side.
  int max_map_px = 800;
  /// ... and a pixel covers at least this much (small maps are not blown up beyond it).
  float min_pixel_m = 0.005f;
  std::string title;
};

/// Faces pointing down (ceilings, undersides) are culled, so a room is seen without its ceiling.
/// Throws InputError when the surface has no vertex.
ColorImage renderOverlay(const Mesh& surface, const std::vector<change::DiscoveredObject>& objects,
                         const OverlayOptions& options);

/// Renders and writes a PNG (Error when the file cannot be written).
void writeOverlayPng(const std::string& path, const Mesh& surface,
                     const std::vector<change::DiscoveredObject>& objects,
                     const OverlayOptions& options);

}  // namespace strata::apps
