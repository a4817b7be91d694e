// Vulkan runtime: device choice, buffers and copies, a real kernel (smoke_add) against the CPU,
// timestamps, error messages, and the validation-error plumbing the other tests rely on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include "strata/core/error.h"
#include "strata/vk/transfer.h"  // private: the staging path, which lavapipe's unified memory skips
#include "strata/vk/vk.h"

namespace strata::vk {
namespace {

constexpr std::uint32_t kSmokeAddWorkgroupSize = 256;  // local_size_x of smoke_add.comp

/// Sets an environment variable for one scope and restores the previous value.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = std::string(old);
    setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (old_) {
      setenv(name_, old_->c_str(), 1);
    } else {
      unsetenv(name_);
    }
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

std::string upper(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return text;
}

/// The message of the DeviceError that `make` throws ("" and a test failure when none).
template <typename Make>
std::string deviceErrorMessage(Make make) {
  try {
    make();
  } catch (const DeviceError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a strata::DeviceError";
  return "";
}

TEST(VkRuntime, CreatesContextWithSaneLimits) {
  auto context = Context::create();
  const DeviceLimits& limits = context->limits();
  EXPECT_FALSE(context->deviceName().empty());
  EXPECT_NE(context->device(), VK_NULL_HANDLE);
  EXPECT_NE(context->queue(), VK_NULL_HANDLE);
  EXPECT_NE(context->commandPool(), VK_NULL_HANDLE);
  EXPECT_GE(limits.max_storage_buffer_range_bytes, 1u << 27);  // Vulkan's minimum is 128 MiB
  EXPECT_GT(limits.max_memory_allocation_bytes, 0u);
  EXPECT_GE(limits.max_workgroup_invocations, kSmokeAddWorkgroupSize);
  EXPECT_GT(limits.subgroup_size, 0u);
  EXPECT_GT(limits.timestamp_valid_bits, 0u);
  EXPECT_GT(limits.timestamp_period_ns, 0.0);
  EXPECT_NE(context->describe().find(context->deviceName()), std::string::npos);
  EXPECT_EQ(context->allocatedBytes(), 0u);
}

TEST(VkRuntime, SmokeAddMatchesCpuExactly) {
  auto context = Context::create();
  constexpr std::uint32_t kCount = 100000;
  std::vector<float> a(kCount), b(kCount), expected(kCount);
  for (std::uint32_t i = 0; i < kCount; ++i) {
    a[i] = 0.5f * static_cast<float>(i) - 1000.0f;
    b[i] = 1.0f / static_cast<float>(i + 1);
    expected[i] = a[i] + b[i];
  }
  const VkDeviceSize bytes = kCount * sizeof(float);
  Buffer a_buffer = Buffer::create(*context, bytes, MemoryUsage::kDeviceLocal, "smoke a");
  Buffer b_buffer = Buffer::create(*context, bytes, MemoryUsage::kDeviceLocal, "smoke b");
  Buffer out_buffer = Buffer::create(*context, bytes, MemoryUsage::kDeviceLocal, "smoke out");
  EXPECT_EQ(context->allocatedBytes(), 3 * bytes);
  upload(*context, a_buffer, a.data(), bytes);
  upload(*context, b_buffer, b.data(), bytes);

  ComputePipeline pipeline = ComputePipeline::create(*context, "smoke_add", 3, sizeof(kCount));
  DescriptorSet set =
      DescriptorSet::create(*context, pipeline, {&a_buffer, &b_buffer, &out_buffer});
  TimestampQueries timestamps = TimestampQueries::create(*context, 2);
  CommandBuffer commands = CommandBuffer::create(*context);
  commands.begin();
  commands.resetQueries(timestamps);
  commands.writeTimestamp(timestamps, 0);
  commands.bind(pipeline, set);
  commands.pushConstants(pipeline, &kCount, sizeof(kCount));
  commands.dispatch((kCount + kSmokeAddWorkgroupSize - 1) / kSmokeAddWorkgroupSize);
  commands.barrier();
  commands.writeTimestamp(timestamps, 1);
  commands.end();
  commands.submitAndWait();

  std::vector<float> result(kCount, -1.0f);
  download(*context, out_buffer, result.data(), bytes);
  std::size_t mismatches = 0;
  for (std::uint32_t i = 0; i < kCount; ++i) mismatches += result[i] != expected[i];
  EXPECT_EQ(mismatches, 0u);
  EXPECT_GE(timestamps.elapsedMs(0, 1), 0.0);
  const std::vector<std::uint64_t> ticks = timestamps.readTicks();
  ASSERT_EQ(ticks.size(), 2u);
  EXPECT_GE(ticks[1], ticks[0]);
}

// The path of a discrete GPU, on any device: device-local memory is never mapped, so copies go
// through the context's persistent staging buffers (kept across calls).
TEST(VkRuntime, StagedMemoryNeverMapsDeviceLocalBuffers) {
  ContextOptions options;
  options.staged_memory = true;
  auto context = Context::create(options);
  EXPECT_TRUE(context->stagedMemory());
  EXPECT_NE(context->describe().find("staged"), std::string::npos);
  std::vector<std::uint32_t> data(1000);
  std::iota(data.begin(), data.end(), 3u);
  Buffer device = Buffer::create(*context, data.size() * 4, MemoryUsage::kDeviceLocal, "device");
  EXPECT_EQ(BufferAccess::hostView(device), nullptr);
  upload(*context, device, data.data(), data.size() * 4);
  const std::uint64_t after_first = context->allocatedBytes();
  upload(*context, device, data.data(), data.size() * 4);
  EXPECT_EQ(context->allocatedBytes(), after_first) << "the staging buffer is kept, not remade";
  std::vector<std::uint32_t> back(data.size(), 0);
  download(*context, device, back.data(), back.size() * 4);
  EXPECT_EQ(back, data);
}

TEST(VkRuntime, UnknownDeviceMemoryModeIsRefused) {
  ScopedEnv env("STRATA_DEVICE_MEMORY", "stagged");
  try {
    Context::create();
    FAIL() << "a misspelt memory mode must not fall back silently";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("STRATA_DEVICE_MEMORY"), std::string::npos) << e.what();
  }
}

TEST(VkRuntime, StagedAndDirectCopiesRoundTrip) {
  auto context = Context::create();
  constexpr std::size_t kWords = 4096;
  std::vector<std::uint32_t> data(kWords);
  std::iota(data.begin(), data.end(), 7u);
  const std::size_t bytes = kWords * sizeof(std::uint32_t);
  Buffer device = Buffer::create(*context, bytes, MemoryUsage::kDeviceLocal, "device");
  Buffer readback = Buffer::create(*context, bytes, MemoryUsage::kHostReadback, "readback");

  // Staging path with an offset, then the public path must agree.
  stagedUpload(*context, device, data.data() + 16, bytes - 64, 64);
  stagedUpload(*context, device, data.data(), 64, 0);
  std::vector<std::uint32_t> back(kWords, 0);
  stagedDownload(*context, device, back.data(), bytes, 0);
  EXPECT_EQ(back, data);
  std::fill(back.begin(), back.end(), 0u);
  download(*context, device, back.data(), bytes);
  EXPECT_EQ(back, data);

  // Device-side copy and fill, read through the mapped readback buffer.
  CommandBuffer commands = CommandBuffer::create(*context);
  commands.begin();
  commands.copy(device, readback, bytes);
  commands.barrier();
  commands.fill(readback, 0xdeadbeefu, 0, 16);
  commands.barrier();
  commands.end();
  commands.submitAndWait();
  ASSERT_NE(readback.mapped(), nullptr);
  const auto* words = static_cast<const std::uint32_t*>(readback.mapped());
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(words[i], 0xdeadbeefu);
  EXPECT_TRUE(std::equal(data.begin() + 4, data.end(), words + 4));

  EXPECT_THROW(upload(*context, device, data.data(), bytes, 4), Error);  // past the end
}

TEST(VkRuntime, BuffersAreMappedByUsageAndHaveAddresses) {
  auto context = Context::create();
  Buffer device = Buffer::create(*context, 256, MemoryUsage::kDeviceLocal, "device");
  Buffer upload_buffer = Buffer::create(*context, 256, MemoryUsage::kHostUpload, "upload");
  Buffer readback = Buffer::create(*context, 256, MemoryUsage::kHostReadback, "readback");
  EXPECT_EQ(device.mapped(), nullptr);
  EXPECT_NE(upload_buffer.mapped(), nullptr);
  EXPECT_NE(readback.mapped(), nullptr);
  EXPECT_NE(device.deviceAddress(), 0u);
  EXPECT_EQ(device.name(), "device");
  EXPECT_EQ(device.size(), 256u);
}

TEST(VkRuntime, MovesTransferOwnershipAndTrackBytes) {
  auto context = Context::create();
  {
    Buffer first = Buffer::create(*context, 1024, MemoryUsage::kDeviceLocal, "first");
    const VkBuffer handle = first.handle();
    Buffer moved(std::move(first));
    EXPECT_FALSE(first.valid());  // NOLINT(bugprone-use-after-move): checking the moved-from state
    EXPECT_EQ(moved.handle(), handle);
    EXPECT_EQ(context->allocatedBytes(), 1024u);

    Buffer second = Buffer::create(*context, 4096, MemoryUsage::kHostUpload, "second");
    EXPECT_EQ(context->allocatedBytes(), 1024u + 4096u);
    second = std::move(moved);  // frees the 4096-byte buffer
    EXPECT_EQ(second.handle(), handle);
    EXPECT_EQ(context->allocatedBytes(), 1024u);
    EXPECT_EQ(context->peakAllocatedBytes(), 1024u + 4096u);

    ComputePipeline pipeline = ComputePipeline::create(*context, "smoke_add", 3, 4, {1u, 2u});
    ComputePipeline other = std::move(pipeline);
    EXPECT_EQ(pipeline.pipeline(), VK_NULL_HANDLE);  // NOLINT(bugprone-use-after-move)
    EXPECT_NE(other.pipeline(), VK_NULL_HANDLE);
    CommandBuffer commands = CommandBuffer::create(*context);
    CommandBuffer commands_moved = std::move(commands);
    commands = std::move(commands_moved);  // back again: no double free either way
    EXPECT_NE(commands.handle(), VK_NULL_HANDLE);
  }
  EXPECT_EQ(context->allocatedBytes(), 0u);
}

TEST(VkRuntime, SelectsDeviceByIndexAndName) {
  const std::vector<PhysicalDeviceInfo> devices = Context::listDevices();
  ASSERT_FALSE(devices.empty());
  ContextOptions by_index;
  by_index.device_selector = "0";
  EXPECT_EQ(Context::create(by_index)->deviceName(), devices[0].name);
  ContextOptions by_name;
  by_name.device_selector = upper(devices[0].name);  // matching ignores case
  EXPECT_EQ(Context::create(by_name)->deviceName(), devices[0].name);
}

TEST(VkRuntime, UnknownSelectorListsAvailableDevices) {
  const std::vector<PhysicalDeviceInfo> devices = Context::listDevices();
  ContextOptions options;
  options.device_selector = "no-such-gpu";
  const std::string message = deviceErrorMessage([&] { Context::create(options); });
  EXPECT_NE(message.find("no-such-gpu"), std::string::npos) << message;
  for (const PhysicalDeviceInfo& d : devices) {
    EXPECT_NE(message.find(d.name), std::string::npos) << message;
  }
  options.device_selector = std::to_string(devices.size());  // one past the last index
  EXPECT_THROW(Context::create(options), DeviceError);
}

TEST(VkRuntime, EnvironmentSelectsDevice) {
  const std::vector<PhysicalDeviceInfo> devices = Context::listDevices();
  {
    ScopedEnv env("STRATA_DEVICE", "no-such-gpu");
    EXPECT_THROW(Context::create(), DeviceError);
    ContextOptions explicit_selector;  // the option wins over the environment
    explicit_selector.device_selector = "0";
    EXPECT_EQ(Context::create(explicit_selector)->deviceName(), devices[0].name);
  }
  ScopedEnv env("STRATA_DEVICE", devices.back().name.c_str());
  EXPECT_EQ(Context::create()->deviceName(), devices.back().name);
}

TEST(VkRuntime, TooLargeBufferNamesItsSize) {
  auto context = Context::create();
  const VkDeviceSize kHuge = VkDeviceSize{1} << 40;  // 1 TiB = 1048576 MiB
  const std::string message = deviceErrorMessage(
      [&] { Buffer::create(*context, kHuge, MemoryUsage::kDeviceLocal, "huge pool"); });
  EXPECT_NE(message.find("huge pool"), std::string::npos) << message;
  EXPECT_NE(message.find("1048576"), std::string::npos) << message;
  EXPECT_EQ(context->allocatedBytes(), 0u);
}

TEST(VkRuntime, PipelineAndBindingErrorsNameTheShader) {
  auto context = Context::create();
  try {
    ComputePipeline::create(*context, "no_such_shader", 1, 0);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_shader"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ComputePipeline::create(*context, "smoke_add", 3, 6), DeviceError);  // not 4k
  ComputePipeline pipeline = ComputePipeline::create(*context, "smoke_add", 3, 4);
  Buffer buffer = Buffer::create(*context, 64, MemoryUsage::kDeviceLocal, "only one");
  EXPECT_THROW(DescriptorSet::create(*context, pipeline, {&buffer}), Error);
  CommandBuffer commands = CommandBuffer::create(*context);
  const std::uint32_t too_many[2] = {1, 2};
  commands.begin();
  EXPECT_THROW(commands.pushConstants(pipeline, too_many, sizeof(too_many)), Error);
  commands.end();
}

/// Records `record(commands)` without submitting it (so the driver never runs it) and returns how
/// many validation errors that produced, acknowledging them so test_main's listener passes.
template <typename Record>
std::uint64_t provokedValidationErrors(Context& context, Record record) {
  const std::uint64_t errors_before = validationErrorCount();
  takeValidationMessages();
  {
    CommandBuffer commands = CommandBuffer::create(context);
    commands.begin();
    record(commands);
    commands.end();
  }
  const std::uint64_t provoked = validationErrorCount() - errors_before;
  EXPECT_EQ(takeValidationMessages().size(), provoked);
  acknowledgeValidationErrors(provoked);
  EXPECT_EQ(validationErrorCount(), errors_before);
  return provoked;
}

// Proves the validation plumbing that every other test relies on: an error the layer reports is
// counted and its message kept.
TEST(VkRuntime, ValidationErrorsAreCounted) {
  auto context = Context::create();
  if (!context->validationEnabled()) GTEST_SKIP() << "run with STRATA_VALIDATION=1 (ctest does)";
  // Invalid on purpose: a dispatch with no pipeline bound.
  EXPECT_GE(provokedValidationErrors(*context, [](CommandBuffer& c) { c.dispatch(1); }), 1u);
}

// Synchronization validation is on: a read of a buffer that the previous dispatch wrote, with no
// barrier between, is reported; with barrier() it is not.
TEST(VkRuntime, MissingBarrierIsReported) {
  auto context = Context::create();
  if (!context->validationEnabled()) GTEST_SKIP() << "run with STRATA_VALIDATION=1 (ctest does)";
  constexpr std::uint32_t kCount = 1024;
  Buffer a = Buffer::create(*context, kCount * 4, MemoryUsage::kDeviceLocal, "a");
  Buffer b = Buffer::create(*context, kCount * 4, MemoryUsage::kDeviceLocal, "b");
  Buffer out = Buffer::create(*context, kCount * 4, MemoryUsage::kDeviceLocal, "out");
  ComputePipeline pipeline = ComputePipeline::create(*context, "smoke_add", 3, 4);
  DescriptorSet writes_out = DescriptorSet::create(*context, pipeline, {&a, &b, &out});
  DescriptorSet reads_out = DescriptorSet::create(*context, pipeline, {&out, &b, &a});
  auto two_dispatches = [&](bool with_barrier) {
    return [&, with_barrier](CommandBuffer& c) {
      c.bind(pipeline, writes_out);
      c.pushConstants(pipeline, &kCount, sizeof(kCount));
      c.dispatch(kCount / 256);
      if (with_barrier) c.barrier();
      c.bind(pipeline, reads_out);
      c.dispatch(kCount / 256);
    };
  };
  EXPECT_GE(provokedValidationErrors(*context, two_dispatches(false)), 1u);
  EXPECT_EQ(provokedValidationErrors(*context, two_dispatches(true)), 0u);
}

}  // namespace
}  // namespace strata::vk
