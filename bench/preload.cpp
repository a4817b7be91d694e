#include "preload.h"

#include <chrono>
#include <cstdio>

#include "strata/core/error.h"
#include "strata/io/open_dataset.h"
#include "machine_info.h"

namespace strata::bench {

PreloadedFrames preloadFrames(const std::string& path, int max_frames) {
  const auto start = std::chrono::steady_clock::now();
  const auto dataset = openDataset(path);
  const std::size_t available = dataset->size();
  const std::size_t count = max_frames > 0 ? static_cast<std::size_t>(max_frames) : available;
  if (count > available) {
    throw InputError("--frames " + std::to_string(count) + " but " + dataset->name() + " has " +
                     std::to_string(available) + " frames");
  }
  PreloadedFrames out;
  out.dataset_name = dataset->name();
  out.intrinsics = dataset->intrinsics();
  out.frames.reserve(count);
  std::fprintf(stderr, "preloading %zu frames from %s\n", count, out.dataset_name.c_str());
  for (std::size_t i = 0; i < count; ++i) out.frames.push_back(dataset->load(i));
  out.load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.host_rss_mib = currentRssMiB();
  return out;
}

}  // namespace strata::bench
