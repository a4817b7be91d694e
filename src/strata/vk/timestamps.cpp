// TimestampQueries: a query pool of device timestamps, read back as ticks or milliseconds.
#include <utility>

#include "strata/core/error.h"
#include "strata/vk/internal/context_impl.h"
#include "strata/vk/internal/result.h"

namespace strata::vk {
namespace {

// Ticks only count timestamp_valid_bits; the rest is undefined and masked off.
std::uint64_t validMask(std::uint32_t valid_bits) {
  return valid_bits >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << valid_bits) - 1;
}

// Results of queries [first, first + count), masked to the valid bits.
// NOTE: no VK_QUERY_RESULT_WAIT_BIT: a query that was never written would block forever. Work is
// complete after CommandBuffer::submitAndWait, so a missing result is a caller's error.
std::vector<std::uint64_t> readMaskedTicks(const Context& context, VkQueryPool pool,
                                           std::uint32_t first, std::uint32_t count) {
  // Pairs of (ticks, availability).
  std::vector<std::uint64_t> results(2 * std::size_t{count});
  const VkResult result = dispatchOf(context).vkGetQueryPoolResults(
      context.device(), pool, first, count, results.size() * sizeof(std::uint64_t), results.data(),
      2 * sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT);
  if (result != VK_NOT_READY) check(result, "vkGetQueryPoolResults");
  const std::uint64_t mask = validMask(context.limits().timestamp_valid_bits);
  std::vector<std::uint64_t> ticks(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    if (results[2 * i + 1] == 0) {
      throw Error("timestamp query " + std::to_string(first + i) +
                  " has no result: reset it, write it (writeTimestamp) and submitAndWait first");
    }
    ticks[i] = results[2 * i] & mask;
  }
  return ticks;
}

}  // namespace

TimestampQueries TimestampQueries::create(Context& context, std::uint32_t count) {
  if (count == 0) throw Error("TimestampQueries: count must be at least 1");
  TimestampQueries q;
  q.context_ = &context;
  noteCreated(context);
  q.count_ = count;
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = count;
  check(dispatchOf(context).vkCreateQueryPool(context.device(), &info, nullptr, &q.pool_),
        "vkCreateQueryPool");
  return q;
}

TimestampQueries::~TimestampQueries() { release(); }

TimestampQueries::TimestampQueries(TimestampQueries&& other) noexcept { *this = std::move(other); }

TimestampQueries& TimestampQueries::operator=(TimestampQueries&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    pool_ = std::exchange(other.pool_, VK_NULL_HANDLE);
    count_ = std::exchange(other.count_, 0);
  }
  return *this;
}

void TimestampQueries::release() {
  if (context_ == nullptr) return;
  if (pool_ != VK_NULL_HANDLE) {
    dispatchOf(*context_).vkDestroyQueryPool(context_->device(), pool_, nullptr);
  }
  noteDestroyed(*context_);
  context_ = nullptr;
  pool_ = VK_NULL_HANDLE;
  count_ = 0;
}

std::vector<std::uint64_t> TimestampQueries::readTicks() const {
  if (context_ == nullptr) throw Error("TimestampQueries::readTicks on an empty query pool");
  return readMaskedTicks(*context_, pool_, 0, count_);
}

double TimestampQueries::elapsedMs(std::uint32_t begin, std::uint32_t end) const {
  if (context_ == nullptr) throw Error("TimestampQueries::elapsedMs on an empty query pool");
  if (begin >= count_ || end >= count_) {
    throw Error("TimestampQueries::elapsedMs: query " +
                std::to_string(begin >= count_ ? begin : end) + " out of range (pool has " +
                std::to_string(count_) + ")");
  }
  const std::uint64_t begin_ticks = readMaskedTicks(*context_, pool_, begin, 1).front();
  const std::uint64_t end_ticks = readMaskedTicks(*context_, pool_, end, 1).front();
  const DeviceLimits& limits = context_->limits();
  // Modular difference: correct across one wrap of a counter narrower than 64 bits.
  const std::uint64_t delta = (end_ticks - begin_ticks) & validMask(limits.timestamp_valid_bits);
  return static_cast<double>(delta) * limits.timestamp_period_ns * 1e-6;
}

}  // namespace strata::vk
