#pragma once
// Options of strata-mapper (the LCM mapping process): where it listens, how it maps, what it
// publishes and how often.
#include <cstddef>
#include <string>

#include "strata/lcm/channels.h"
#include "strata/map/map_config.h"

namespace CLI {
class App;
}

namespace strata::apps {

struct MapperChannels {
  std::string rgbd = lcm_io::kRgbdChannel;
  std::string camera_info = lcm_io::kCameraInfoChannel;
  std::string pose = lcm_io::kPoseChannel;
  std::string command = lcm_io::kCommandChannel;
  std::string mesh = lcm_io::kMeshChannel;
  std::string esdf = lcm_io::kEsdfChannel;
  std::string stats = lcm_io::kStatsChannel;
  std::string change = lcm_io::kChangeChannel;
  std::string objects = lcm_io::kObjectsChannel;
  std::string keyframe = lcm_io::kKeyframeChannel;
};

struct MapperOptions {
  /// LCM URL to listen on; output_url "" publishes on the same.
  std::string url = lcm_io::kDefaultUrl;
  std::string output_url;
  MapperChannels channels;
  /// Map settings; the voxel default is 5 cm (a live map on a CPU device keeps up at that size).
  MapConfig map = defaultMapperMapConfig();
  /// Loaded at start when it exists (the mapper resumes it; a corrupt file is refused, untouched);
  /// written atomically on SAVE_MAP without a path, every save_every_s and on SIGINT/SIGTERM;
  /// "" = none of these.
  std::string map_path = "strata_map.strata";
  /// Seconds between saves of the map to map_path while frames are being fused (a kill loses at
  /// most this much); 0: only on SAVE_MAP and on exit.
  double save_every_s = 60.0;
  /// Mesh updates of changed blocks per second; <= 0: after every fused frame (lowest latency).
  double mesh_rate_hz = 2.0;
  /// ESDF slices per second (the ESDF is updated incrementally then); 0: no ESDF.
  double esdf_rate_hz = 1.0;
  float esdf_slice_z_m = 1.0f;
  /// map_stats_t is published after every fused frame and at least this often.
  double stats_rate_hz = 1.0;
  /// Frames waiting to be fused; more arriving drop the oldest (counted).
  std::size_t queue_capacity = 4;
  /// Change detection per session: each frame is fused once, into the session's own layer (with
  /// constant weights and observed free space, as change detection needs); change events on
  /// session end.
  bool change_detection = true;
  /// Change detection: a voxel differs between a session and the static map by more than this
  /// many voxels (lower finds smaller moves, labels more noise), and counts as observed in a
  /// session once this many frames saw it (fewer: more of the session counts, noisier).
  float change_threshold_voxels = 2.5f;
  float change_min_weight = 3.0f;
  /// With change detection: the objects each ended session found join the object database
  /// (objects/object_database.h: matched to the models of earlier sessions, merged, or new
  /// models); every model a session created or extended is published (object_update_t).
  bool object_database = true;
  /// The database file: loaded at start when it exists (a corrupt or newer one is refused and
  /// left untouched), written atomically after every session end and on exit. "" with a map
  /// path: beside the map (its name with ".objects"); "" without one: kept in memory only.
  std::string objects_path;
  /// objects_path, or the map path's sibling, or "".
  std::string objectsFile() const;
  /// Score every frame against the map before fusing it (keyframe_score_t): a raycast of a
  /// sparse pixel grid, a few ms per frame.
  bool keyframe_scores = true;
  std::string device;  // Vulkan device index or name substring
  bool quiet = false;

  static MapConfig defaultMapperMapConfig();
  /// Throws InputError naming the bad option.
  void validate() const;
};

/// Registers strata-mapper's options on `app`.
void addMapperOptions(CLI::App& app, MapperOptions& options);

}  // namespace strata::apps
