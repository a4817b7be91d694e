#pragma once
// Publishing one LCM message for strata-play: a failed publish is an error naming the channel.
#include <lcm/lcm-cpp.hpp>

#include <cstddef>
#include <string>

#include "strata/core/error.h"

namespace strata::apps::internal {

/// Publishes `message` on `channel`; returns its encoded size in bytes. Throws InputError naming
/// the channel and the message type when LCM refuses it.
template <typename Message>
std::size_t publishOrThrow(lcm::LCM& lcm, const std::string& channel, const Message& message) {
  if (lcm.publish(channel, &message) != 0) {
    throw InputError("LCM could not publish on " + channel + " (" + Message::getTypeName() + ")");
  }
  return static_cast<std::size_t>(message.getEncodedSize());
}

}  // namespace strata::apps::internal
