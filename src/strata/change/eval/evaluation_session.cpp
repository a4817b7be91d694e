#include "strata/change/eval/evaluation_session.h"

#include <cstdio>

namespace strata::change {

RecordingSession::RecordingSession(std::shared_ptr<const sim::SimSessionDataset> session,
                                   float spacing_m)
    : session_(std::move(session)), seen_(std::make_unique<VisibleSurface>(spacing_m)) {}

RgbdFrame RecordingSession::load(std::size_t index) const {
  sim::SimulatedFrame frame = session_->render(index);
  // The truth is placed from the true pose, whatever (drifted) pose the mapper is given.
  seen_->addFrame(frame, intrinsics(), session_->truePoses().at(index));
  char frame_name[64];
  std::snprintf(frame_name, sizeof(frame_name), "session %d frame %zu", session_->session(), index);
  return sim::makeRgbdFrame(std::move(frame), session_->givenPoses().at(index),
                            session_->timestamp(index), frame_name);
}

}  // namespace strata::change
