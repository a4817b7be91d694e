#pragma once
// The work of `strata fuse`, split into steps so each stays small.
#include <memory>
#include <string>
#include <vector>

#include "cli/fuse_command.h"
#include "strata/io/open_dataset.h"
#include "strata/io/tum_format.h"
#include "strata/mapper/mapper.h"
#include "strata/map/tsdf_map.h"
#include "strata/mesh/mesh.h"
#include "strata/vk/vk.h"

namespace strata::sim {
class AnalyticDataset;
}

namespace strata::apps {

class FuseSession {
 public:
  explicit FuseSession(const FuseOptions& options);
  ~FuseSession();

  /// Fuses the frames. Returns false when a frame failed part-way (the error is printed with
  /// what stays at the output paths; the caller then writes nothing). With --skip-bad-frames a
  /// frame refused as bad input (unreadable, wrong size, bad pose) is skipped and counted.
  bool run();
  /// Downloads the map, writes map / mesh / rendering / ESDF slice as requested. Returns false
  /// when the map or the ESDF slice could not be written (the reason is printed and kept for
  /// the summary); a failed map save leaves the file at the path as it was.
  bool writeOutputs();
  /// One paragraph: frames, blocks, voxels, ms per frame by kernel (ESDF too), memory, device,
  /// accuracy.
  void printSummary() const;

 private:
  /// False when the frame was not fused (lost by tracking).
  bool fuseFrame(const RgbdFrame& frame);
  void updateEsdf();
  void renderView();
  bool writeEsdfSlice();
  /// Saves the map; on failure prints why and what is at the path now, and returns false.
  bool saveMapFile();
  /// What a failed save left at the map path (the previous file, or nothing).
  std::string previousMapNote() const;
  std::string esdfSummary() const;
  /// Tracks the frame and fuses it when tracking is ok (--track).
  bool trackFrame(const RgbdFrame& frame);
  bool writeTrajectory();
  std::string trackingSummary() const;

  FuseOptions options_;
  std::unique_ptr<Dataset> dataset_;
  const sim::AnalyticDataset* analytic_ = nullptr;  // set when fusing the built-in scene
  std::unique_ptr<vk::Context> context_;
  std::unique_ptr<Mapper> mapper_;    // the device path (none with --reference)
  EsdfUpdateStats esdf_totals_;       // summed over frames
  std::string esdf_slice_problem_;    // why the ESDF slice was not written
  std::string map_save_problem_;      // why the map was not saved
  TsdfMap map_;
  Mesh mesh_;
  std::vector<std::size_t> frame_indices_;
  std::size_t fused_ = 0;
  FrameStats totals_;
  double reference_ms_ = 0.0;
  double wall_s_ = 0.0;
  std::string failure_;
  std::size_t skipped_ = 0;           // --skip-bad-frames
  std::string first_skipped_;         // the first skipped frame's error
  std::vector<std::string> written_;
  Eigen::Isometry3d last_pose_ = Eigen::Isometry3d::Identity();
  // --track: totals over the tracked frames (the first frame is not tracked), the trajectory.
  std::size_t tracked_ = 0;
  std::size_t lost_ = 0;
  std::string first_lost_reason_;
  double track_wall_ms_ = 0.0;
  double track_raycast_ms_ = 0.0;
  double track_equations_ms_ = 0.0;
  int track_iterations_ = 0;
  // Stated uncertainty (TrackResult::translation_sigma_m) of the fused tracked frames.
  std::vector<double> track_sigma_m_;
  double fusion_wall_ms_ = 0.0;
  std::vector<tum::TimedPose> estimate_, dataset_poses_;  // of the fused frames, for the ATE
};

}  // namespace strata::apps
