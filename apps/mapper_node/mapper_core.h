#pragma once
// The mapper's work without LCM, on strata::Mapper: fuse a frame (scored first), the mesh of
// changed blocks, an ESDF slice, sessions and their change events, saving the map — each turned
// into or out of its message. strata-mapper's node calls it from its one worker thread; tests call
// it directly. With change detection on, every frame is fused once, into the session's layer.
// The object database is updated at a session end on a thread of its own (seconds for a room),
// so the frames of the next session keep being fused meanwhile; its updates are handed over when
// it is done (objectUpdatesReady / takeObjectUpdates).
// Thread safety: not thread safe (the database thread is private: every method that reads or
// writes the database waits for it first).
#include <cstdint>
#include <future>
#include <memory>
#include <string>
#include <vector>

#include "strata/lcm/frame_assembler.h"
#include "strata/mapper/mapper.h"
#include "mapper_node/mapper_options.h"
#include "strata/change_event_t.hpp"
#include "strata/esdf_slice_t.hpp"
#include "strata/keyframe_score_t.hpp"
#include "strata/mesh_update_t.hpp"
#include "strata/object_update_t.hpp"
#include "strata/vk/vk.h"

namespace strata::objects {
class ObjectDatabase;
}

namespace strata::apps {

/// The Mapper configuration strata-mapper's options ask for.
MapperConfig mapperConfig(const MapperOptions& options);

class MapperCore {
 public:
  /// `context` must outlive the core. Throws InputError for invalid options. `start`
  /// (optional): the saved file to continue, e.g. the last one saved before a kill; its voxel
  /// size and truncation replace the options'. Frames then fuse into it exactly as they would
  /// have into the mapper that saved it: with change detection, a mapper state continues its
  /// open session (or the next frame opens a new one after its ended sessions), and a plain map
  /// is the static estimate of an ended session (Mapper::resume).
  MapperCore(vk::Context& context, const MapperOptions& options,
             const MapFileContents* start = nullptr);
  ~MapperCore();

  /// Fuses one frame (opening a session when none is open). Throws InputError for a bad frame
  /// and DeviceError when the device is full; the map is then as it was before the frame.
  /// `score` (optional): the frame's keyframe score against the map before it; returns whether
  /// one was made (keyframe scoring on).
  bool fuse(const lcm_io::ReadyFrame& frame, keyframe_score_t* score = nullptr);

  /// The blocks changed since the last update (full: every block with a surface); false when
  /// nothing changed (no message then). Downloads the changed blocks (device -> host).
  bool meshUpdate(bool full, std::int64_t utime, mesh_update_t* update);
  /// Brings the ESDF up to date and cuts the slice; false without ESDF or frames.
  bool esdfSlice(std::int64_t utime, esdf_slice_t* slice);

  /// Opens a new session (ending an open one first: its events are returned).
  std::vector<change_event_t> startSession(std::int64_t utime);
  /// Ends the open session; its discovered objects as events. Throws InputError when none is open.
  std::vector<change_event_t> stopSession(std::int64_t utime);

  /// True when a session end's database update has finished and its updates wait to be taken
  /// (or it failed: takeObjectUpdates then throws its error). Does not wait.
  bool objectUpdatesReady() const;
  /// The object database's updates of the session ends handed over since the last call (one per
  /// model each created or extended), once; waits for an update still running when `wait`.
  /// Empty without the database. Rethrows the error of a failed update (the database is then as
  /// before that session: ObjectDatabase::addSession changes nothing when it throws).
  std::vector<object_update_t> takeObjectUpdates(bool wait = false);
  /// Writes the object database atomically to options.objectsFile() (after waiting for an update
  /// still running); false when there is no database or no file. Throws Error when the write
  /// fails (the previous file stays).
  bool saveObjects();
  /// nullptr without the database. Waits for an update still running.
  const objects::ObjectDatabase* objectDatabase();

  /// Downloads the map and writes it atomically (map_file.h).
  void saveMap(const std::string& path);
  /// Host copy of the live map (device -> host).
  TsdfMap downloadMap();

  std::int64_t framesFused() const { return frames_fused_; }
  std::int64_t lastFrameUtime() const { return last_frame_utime_; }
  double lastFuseMs() const { return last_fuse_ms_; }
  double meanFuseMs() const { return frames_fused_ ? total_fuse_ms_ / frames_fused_ : 0.0; }
  std::uint32_t blocks() const { return mapper_->blockCount(); }
  /// Bytes held in device buffers by the context (vk::Context::allocatedBytes()).
  std::uint64_t deviceBytes() const { return context_.allocatedBytes(); }
  int session() const { return session_; }
  bool sessionActive() const { return mapper_->sessionOpen(); }
  const MapConfig& mapConfig() const { return mapper_->config().map; }
  Mapper& mapper() { return *mapper_; }

 private:
  std::vector<change_event_t> endSession(std::int64_t utime);
  void addToObjectDatabase(SessionResult result, std::int64_t utime);
  /// The database's work for one session end, on the database thread.
  std::vector<object_update_t> objectUpdatesOf(const SessionResult& result, int session,
                                               std::int64_t utime);
  /// Waits for a running database update and keeps its updates (or its error) for
  /// takeObjectUpdates.
  void finishObjectJob();

  vk::Context& context_;
  MapperOptions options_;
  std::unique_ptr<Mapper> mapper_;
  std::int64_t mesh_sequence_ = 0;
  std::int64_t frames_fused_ = 0;
  std::int64_t last_frame_utime_ = 0;
  double last_fuse_ms_ = 0.0;
  double total_fuse_ms_ = 0.0;
  int session_ = -1;
  std::unique_ptr<objects::ObjectDatabase> objects_;
  int next_object_session_ = 0;  // the database's session numbers continue across restarts
  std::vector<object_update_t> object_updates_;
  std::future<std::vector<object_update_t>> object_job_;  // the running database update
  std::exception_ptr object_error_;                       // of the last finished one
};

}  // namespace strata::apps
