#pragma once
// Strata's Vulkan compute runtime: RAII wrappers made by fallible factories (they throw
// strata::DeviceError naming the failed call and what to install or change). Host<->device copies
// are explicit free functions or CommandBuffer::copy, never hidden in getters.
// Thread safety: a Context and the objects made from it are used from one thread at a time.
// Lifetime: every object made from a Context (Buffer, ComputePipeline, DescriptorSet,
// TimestampQueries, CommandBuffer) keeps a pointer to it and must be destroyed before it.
// NOTE: the Vulkan loader is opened at run time (dlopen), so this header provides types only.
#ifndef VK_NO_PROTOTYPES
#define VK_NO_PROTOTYPES
#endif
#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace strata::vk {

/// Throws DeviceError("<call> failed: <VkResult name>[: advice]") unless result == VK_SUCCESS.
void check(VkResult result, const char* call);

struct ContextOptions {
  /// "" picks automatically (discrete GPU, integrated, virtual, then CPU/lavapipe). Otherwise a
  /// device index ("0") or a case-insensitive substring of the device name ("llvmpipe").
  /// When empty, the environment variable STRATA_DEVICE is used if set.
  std::string device_selector;
  /// Enable VK_LAYER_KHRONOS_validation, with synchronization validation (missing barriers).
  /// Also enabled when env STRATA_VALIDATION=1.
  bool enable_validation = false;
  /// Log the chosen device and its limits once to stderr.
  bool log_device = true;
  /// Never map device-local memory, even where it is host-visible (lavapipe, integrated GPUs):
  /// every host<->device copy then takes the staging path a discrete GPU needs, so that path is
  /// tested on any machine. Also on when env STRATA_DEVICE_MEMORY=staged.
  bool staged_memory = false;
};

struct DeviceLimits {
  std::uint64_t max_storage_buffer_range_bytes = 0;
  std::uint64_t max_memory_allocation_bytes = 0;
  std::uint32_t max_workgroup_invocations = 0;
  std::uint32_t max_shared_memory_bytes = 0;
  std::uint32_t subgroup_size = 0;
  double timestamp_period_ns = 1.0;
  std::uint32_t timestamp_valid_bits = 0;
  std::uint64_t device_local_heap_bytes = 0;
  /// What the process may still allocate in that heap when the context was made
  /// (VK_EXT_memory_budget: budget minus usage); 0 where the device does not report it.
  std::uint64_t device_local_budget_bytes = 0;
  /// Optional features, enabled when the device has them (VK_EXT_shader_atomic_float/_float2):
  /// atomicAdd / atomicMin / atomicMax on float32 in storage buffers.
  bool float32_atomic_add = false;
  bool float32_atomic_min_max = false;
};

struct PhysicalDeviceInfo {
  std::uint32_t index = 0;
  std::string name;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
};

/// Instance + logical device + one compute queue. Required features (checked with a clear error):
/// Vulkan 1.2, shaderInt64, shaderBufferInt64Atomics, bufferDeviceAddress, timestamp queries,
/// subgroup shuffle and vote in compute (subgroups of at least 4), workgroups of 512 invocations
/// (sizes up to 256x16x8). The memory budget (VK_EXT_memory_budget) is read where present.
class Context {
 public:
  static std::unique_ptr<Context> create(const ContextOptions& options = {});
  /// Every physical device the loader reports (throws DeviceError when there is no loader).
  static std::vector<PhysicalDeviceInfo> listDevices();
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const;
  VkPhysicalDevice physicalDevice() const;
  VkDevice device() const;
  VkQueue queue() const;
  std::uint32_t queueFamily() const;
  VkCommandPool commandPool() const;
  const std::string& deviceName() const;
  VkPhysicalDeviceType deviceType() const;
  const DeviceLimits& limits() const;
  /// One line: name, type, driver, the limits above.
  std::string describe() const;
  bool validationEnabled() const;
  /// ContextOptions::staged_memory (or STRATA_DEVICE_MEMORY=staged) is in effect.
  bool stagedMemory() const;

  /// Index of a memory type with all `required` flags (preferring `preferred` as well).
  std::uint32_t findMemoryType(std::uint32_t type_bits, VkMemoryPropertyFlags required,
                               VkMemoryPropertyFlags preferred = 0) const;

  /// Bytes currently allocated through Buffer, and the peak over the context's life.
  std::uint64_t allocatedBytes() const;
  std::uint64_t peakAllocatedBytes() const;

  struct Impl;

 private:
  explicit Context(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  friend class Buffer;
  friend struct ContextAccess;  // src/strata/vk/context_impl.h: the other wrappers' dispatch table
};

/// Validation-layer errors seen by any Context in this process (warnings are not counted).
std::uint64_t validationErrorCount();
/// The messages of those errors since the last call (for test failure output).
std::vector<std::string> takeValidationMessages();
/// For tests that provoke validation errors on purpose: subtracts `count` errors from
/// validationErrorCount() so the per-test validation listener does not fail the test.
void acknowledgeValidationErrors(std::uint64_t count);

enum class MemoryUsage {
  kDeviceLocal,   // device-local; host copies go through a staging buffer
  kHostUpload,    // host-visible, coherent, persistently mapped; CPU writes, GPU reads
  kHostReadback,  // host-visible, cached if possible, persistently mapped; GPU writes, CPU reads
};

/// A VkBuffer with its own VkDeviceMemory. Usage always includes storage, transfer src/dst and
/// shader device address. Throws DeviceError naming the buffer and size when allocation fails.
class Buffer {
 public:
  static Buffer create(Context& context, VkDeviceSize size_bytes, MemoryUsage usage,
                       const std::string& debug_name);
  Buffer() = default;
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  bool valid() const { return buffer_ != VK_NULL_HANDLE; }
  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_bytes_; }
  VkDeviceAddress deviceAddress() const { return address_; }
  /// Mapped pointer for kHostUpload/kHostReadback buffers, nullptr otherwise.
  void* mapped() const { return mapped_; }
  const std::string& name() const { return name_; }
  /// Unique over the process for every created buffer (moves keep it; 0 when empty): what caches
  /// keyed on buffers compare, since Vulkan may reuse a destroyed buffer's handle.
  std::uint64_t id() const { return id_; }

 private:
  void release();
  Context* context_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_bytes_ = 0;
  VkDeviceAddress address_ = 0;
  void* mapped_ = nullptr;
  // Private host view of a kDeviceLocal buffer whose memory is also host-visible, coherent and
  // cached (lavapipe, integrated GPUs): upload/download memcpy through it instead of staging.
  void* host_view_ = nullptr;
  std::uint64_t id_ = 0;
  std::string name_;
  friend struct BufferAccess;  // src/strata/vk/transfer.h
};

/// Explicit host->device copy (memcpy for mapped buffers, staging + one submit otherwise). Blocks.
void upload(Context& context, Buffer& dst, const void* src, std::size_t bytes,
            std::size_t dst_offset = 0);
/// Explicit device->host copy. Blocks until the data is on the host.
void download(Context& context, const Buffer& src, void* dst, std::size_t bytes,
              std::size_t src_offset = 0);

/// A compute pipeline over `storage_buffer_count` storage buffers at set 0, bindings 0..n-1, with
/// `push_constant_bytes` of push constants and optional uint32 specialization constants (ids
/// 0..k-1).
class ComputePipeline {
 public:
  static ComputePipeline create(Context& context, const std::string& shader_name,
                                std::uint32_t storage_buffer_count,
                                std::uint32_t push_constant_bytes,
                                const std::vector<std::uint32_t>& specialization = {});
  ComputePipeline() = default;
  ~ComputePipeline();
  ComputePipeline(ComputePipeline&& other) noexcept;
  ComputePipeline& operator=(ComputePipeline&& other) noexcept;
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;

  VkPipeline pipeline() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }
  VkDescriptorSetLayout setLayout() const { return set_layout_; }
  std::uint32_t storageBufferCount() const { return storage_buffer_count_; }
  std::uint32_t pushConstantBytes() const { return push_constant_bytes_; }
  const std::string& name() const { return name_; }

 private:
  void release();
  Context* context_ = nullptr;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkShaderModule module_ = VK_NULL_HANDLE;
  std::uint32_t storage_buffer_count_ = 0;
  std::uint32_t push_constant_bytes_ = 0;
  std::string name_;
};

/// A descriptor set (with its own small pool) binding `buffers` in order to a pipeline's set 0.
/// Cheap; make a new one when a buffer is reallocated. A buffer larger than
/// limits().max_storage_buffer_range_bytes is bound over its first max_storage_buffer_range_bytes;
/// reach the rest through deviceAddress().
class DescriptorSet {
 public:
  static DescriptorSet create(Context& context, const ComputePipeline& pipeline,
                              const std::vector<const Buffer*>& buffers);
  DescriptorSet() = default;
  ~DescriptorSet();
  DescriptorSet(DescriptorSet&& other) noexcept;
  DescriptorSet& operator=(DescriptorSet&& other) noexcept;
  DescriptorSet(const DescriptorSet&) = delete;
  DescriptorSet& operator=(const DescriptorSet&) = delete;
  VkDescriptorSet handle() const { return set_; }

 private:
  void release();
  Context* context_ = nullptr;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

/// A pool of timestamp queries; values are converted to milliseconds with the device period.
class TimestampQueries {
 public:
  static TimestampQueries create(Context& context, std::uint32_t count);
  TimestampQueries() = default;
  ~TimestampQueries();
  TimestampQueries(TimestampQueries&& other) noexcept;
  TimestampQueries& operator=(TimestampQueries&& other) noexcept;
  TimestampQueries(const TimestampQueries&) = delete;
  TimestampQueries& operator=(const TimestampQueries&) = delete;

  VkQueryPool handle() const { return pool_; }
  std::uint32_t count() const { return count_; }
  /// Milliseconds between queries `begin` and `end` (both written and the work completed).
  double elapsedMs(std::uint32_t begin, std::uint32_t end) const;
  /// Raw results of all queries, in ticks (masked to the valid bits). Throws when one has no
  /// result yet: every query must be written and its command buffer waited for.
  std::vector<std::uint64_t> readTicks() const;

 private:
  void release();
  Context* context_ = nullptr;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  std::uint32_t count_ = 0;
};

/// A primary command buffer with its own fence. Record, then submitAndWait().
class CommandBuffer {
 public:
  static CommandBuffer create(Context& context);
  CommandBuffer() = default;
  ~CommandBuffer();
  CommandBuffer(CommandBuffer&& other) noexcept;
  CommandBuffer& operator=(CommandBuffer&& other) noexcept;
  CommandBuffer(const CommandBuffer&) = delete;
  CommandBuffer& operator=(const CommandBuffer&) = delete;

  void begin();
  void bind(const ComputePipeline& pipeline, const DescriptorSet& set);
  void pushConstants(const ComputePipeline& pipeline, const void* data, std::size_t bytes);
  void dispatch(std::uint32_t groups_x, std::uint32_t groups_y = 1, std::uint32_t groups_z = 1);
  /// Dispatch with the group counts a kernel wrote: three uint32 at `offset_bytes` of `args`
  /// (VkDispatchIndirectCommand; offset a multiple of 4).
  void dispatchIndirect(const Buffer& args, VkDeviceSize offset_bytes = 0);
  /// Full memory barrier between compute/transfer writes and later compute/transfer/host access.
  void barrier();
  void copy(const Buffer& src, Buffer& dst, VkDeviceSize bytes, VkDeviceSize src_offset = 0,
            VkDeviceSize dst_offset = 0);
  /// vkCmdFillBuffer; offset and bytes multiples of 4 (bytes = VK_WHOLE_SIZE for all).
  void fill(Buffer& buffer, std::uint32_t value, VkDeviceSize offset = 0,
            VkDeviceSize bytes = VK_WHOLE_SIZE);
  void resetQueries(TimestampQueries& queries);
  void writeTimestamp(TimestampQueries& queries, std::uint32_t index);
  void end();
  /// Submits to the context's queue and waits. VK_ERROR_DEVICE_LOST becomes a DeviceError that
  /// says the device was lost and the map on the host is intact.
  void submitAndWait();
  VkCommandBuffer handle() const { return command_buffer_; }

 private:
  void release();
  Context* context_ = nullptr;
  VkCommandBuffer command_buffer_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
};

}  // namespace strata::vk
