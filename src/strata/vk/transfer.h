#pragma once
// Private: host<->device copies (upload/download in vk.h), and the staging path on its own so
// tests can run it on devices whose memory is all host-visible (lavapipe).
#include <cstddef>

#include "strata/vk/vk.h"

namespace strata::vk {

/// The wrappers' way into a Buffer (friend of Buffer).
struct BufferAccess {
  /// Where the host can read/write the buffer directly: mapped() or the private host view of
  /// host-visible, coherent, cached device-local memory; nullptr when staging is needed.
  static void* hostView(const Buffer& buffer) {
    return buffer.mapped_ != nullptr ? buffer.mapped_ : buffer.host_view_;
  }
  static const Context* context(const Buffer& buffer) { return buffer.context_; }
};

/// Copies through a kHostUpload staging buffer and a copy command, in chunks; blocks.
void stagedUpload(Context& context, Buffer& dst, const void* src, std::size_t bytes,
                  std::size_t dst_offset);
/// Copies through a kHostReadback staging buffer and a copy command, in chunks; blocks.
void stagedDownload(Context& context, const Buffer& src, void* dst, std::size_t bytes,
                    std::size_t src_offset);

/// Throws strata::Error unless [offset, offset + bytes) lies inside `buffer` (made on `context`).
void requireRange(const Context& context, const Buffer& buffer, std::size_t offset,
                  std::size_t bytes, const char* operation);

}  // namespace strata::vk
