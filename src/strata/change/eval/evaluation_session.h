#pragma once
// A simulated session that records what it shows: a Dataset whose load() renders the frame once,
// adds its exact surface points to a VisibleSurface (ground truth of what the session saw), and
// hands the sensor frame on like SimSessionDataset::load.
#include <memory>

#include "strata/change/eval/evaluation_visibility.h"
#include "strata/io/open_dataset.h"
#include "strata/sim/session/sim_session.h"

namespace strata::change {

/// Thread safety: none (load() adds to the recorded surface).
class RecordingSession : public Dataset {
 public:
  explicit RecordingSession(std::shared_ptr<const sim::SimSessionDataset> session,
                            float spacing_m = 0.02f);

  std::string name() const override { return session_->name(); }
  std::size_t size() const override { return session_->size(); }
  CameraIntrinsics intrinsics() const override { return session_->intrinsics(); }
  RgbdFrame load(std::size_t index) const override;

  const sim::SimSessionDataset& session() const { return *session_; }
  const VisibleSurface& seen() const { return *seen_; }

 private:
  std::shared_ptr<const sim::SimSessionDataset> session_;
  std::unique_ptr<VisibleSurface> seen_;  // grows in the const load(): what was looked at
};

}  // namespace strata::change
