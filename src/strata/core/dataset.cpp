#include "strata/core/dataset.h"

namespace strata {

Dataset::~Dataset() = default;

FrameStamp Dataset::stamp(std::size_t index) const {
  const RgbdFrame frame = load(index);
  return {frame.timestamp_s, frame.T_W_C};
}

}  // namespace strata
