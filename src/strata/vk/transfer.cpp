// upload/download: memcpy where the host can reach the memory, otherwise staging + copy command.
#include "strata/vk/transfer.h"

#include <algorithm>
#include <cstring>

#include "strata/core/error.h"
#include "strata/vk/internal/context_impl.h"

namespace strata::vk {
namespace {

// Bounds the staging memory of a large copy; each chunk is one submit (the copy itself dominates).
constexpr std::size_t kStagingChunkBytes = std::size_t{64} << 20;

}  // namespace

void requireRange(const Context& context, const Buffer& buffer, std::size_t offset,
                  std::size_t bytes, const char* operation) {
  if (!buffer.valid()) throw Error(std::string(operation) + ": the buffer is empty (moved from?)");
  if (BufferAccess::context(buffer) != &context) {
    throw Error(std::string(operation) + ": buffer '" + buffer.name() +
                "' belongs to another Vulkan context");
  }
  // Written so that offset + bytes cannot overflow.
  if (offset > buffer.size() || bytes > buffer.size() - offset) {
    throw Error(std::string(operation) + ": " + std::to_string(bytes) + " bytes at offset " +
                std::to_string(offset) + " lie outside buffer '" + buffer.name() + "' of " +
                std::to_string(buffer.size()) + " bytes");
  }
}

void upload(Context& context, Buffer& dst, const void* src, std::size_t bytes,
            std::size_t dst_offset) {
  requireRange(context, dst, dst_offset, bytes, "upload");
  if (bytes == 0) return;
  if (void* view = BufferAccess::hostView(dst)) {
    // Coherent memory: the next vkQueueSubmit makes these writes visible to the device.
    std::memcpy(static_cast<char*>(view) + dst_offset, src, bytes);
    return;
  }
  stagedUpload(context, dst, src, bytes, dst_offset);
}

void download(Context& context, const Buffer& src, void* dst, std::size_t bytes,
              std::size_t src_offset) {
  requireRange(context, src, src_offset, bytes, "download");
  if (bytes == 0) return;
  if (const void* view = BufferAccess::hostView(src)) {
    // NOTE: device writes are visible here when the command buffer that made them ended with
    // barrier() (its destination includes the host) and was waited for.
    std::memcpy(dst, static_cast<const char*>(view) + src_offset, bytes);
    return;
  }
  stagedDownload(context, src, dst, bytes, src_offset);
}

namespace {

/// The context's persistent staging buffer of `usage`, at least `bytes` long. Caller holds the
/// staging mutex.
Buffer& stagingBuffer(Context& context, MemoryUsage usage, std::size_t bytes) {
  Context::Impl& impl = ContextAccess::impl(context);
  std::unique_ptr<Buffer>& slot =
      usage == MemoryUsage::kHostUpload ? impl.staging_upload : impl.staging_download;
  if (!slot || slot->size() < bytes) {
    slot.reset();  // free the old one first: the new one may be large
    slot = std::make_unique<Buffer>(Buffer::create(
        context, bytes, usage,
        usage == MemoryUsage::kHostUpload ? "staging upload" : "staging download"));
  }
  return *slot;
}

CommandBuffer& stagingCommands(Context& context) {
  Context::Impl& impl = ContextAccess::impl(context);
  if (!impl.staging_commands) {
    impl.staging_commands = std::make_unique<CommandBuffer>(CommandBuffer::create(context));
  }
  return *impl.staging_commands;
}

}  // namespace

void stagedUpload(Context& context, Buffer& dst, const void* src, std::size_t bytes,
                  std::size_t dst_offset) {
  requireRange(context, dst, dst_offset, bytes, "upload");
  if (bytes == 0) return;
  const std::size_t chunk_bytes = std::min(bytes, kStagingChunkBytes);
  std::lock_guard<std::mutex> lock(ContextAccess::impl(context).staging_mutex);
  Buffer& staging = stagingBuffer(context, MemoryUsage::kHostUpload, chunk_bytes);
  CommandBuffer& commands = stagingCommands(context);
  for (std::size_t done = 0; done < bytes; done += chunk_bytes) {
    const std::size_t n = std::min(chunk_bytes, bytes - done);
    std::memcpy(staging.mapped(), static_cast<const char*>(src) + done, n);
    commands.begin();
    commands.copy(staging, dst, n, 0, dst_offset + done);
    commands.barrier();  // later compute/transfer work sees the copy
    commands.end();
    commands.submitAndWait();
  }
}

void stagedDownload(Context& context, const Buffer& src, void* dst, std::size_t bytes,
                    std::size_t src_offset) {
  requireRange(context, src, src_offset, bytes, "download");
  if (bytes == 0) return;
  const std::size_t chunk_bytes = std::min(bytes, kStagingChunkBytes);
  std::lock_guard<std::mutex> lock(ContextAccess::impl(context).staging_mutex);
  Buffer& staging = stagingBuffer(context, MemoryUsage::kHostReadback, chunk_bytes);
  CommandBuffer& commands = stagingCommands(context);
  for (std::size_t done = 0; done < bytes; done += chunk_bytes) {
    const std::size_t n = std::min(chunk_bytes, bytes - done);
    commands.begin();
    commands.copy(src, staging, n, src_offset + done, 0);
    commands.barrier();  // makes the copy visible to the host reads below
    commands.end();
    commands.submitAndWait();
    std::memcpy(static_cast<char*>(dst) + done, staging.mapped(), n);
  }
}

}  // namespace strata::vk
