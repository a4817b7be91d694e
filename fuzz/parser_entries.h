#pragma once
// The entry point of every fuzz target: one function per parser of outside data, fed the raw input
// as the reader sees a file's or a message's bytes. Shared by the libFuzzer targets (fuzz_<name>.cpp)
// and the regression test that replays test/data/fuzz_regressions/<name>/, so both run the very
// same code. Each throws InputError when it refuses an input; anything else escaping is a bug.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "strata/core/error.h"

namespace strata::fuzz {

using Entry = void (*)(const std::uint8_t* data, std::size_t size);

/// The entry of fuzz target `name` (e.g. "fuzz_map_file"); nullptr for an unknown name.
Entry findEntry(const std::string& name);

/// What every libFuzzer target does with an input: an InputError is the expected refusal of bad
/// input; anything else escaping (another exception, a crash, a sanitizer report, a leak) is a
/// finding that libFuzzer reports.
inline int refuseOrAccept(Entry entry, const std::uint8_t* data, std::size_t size) {
  try {
    entry(data, size);
  } catch (const InputError&) {
  }
  return 0;
}

/// Every target's name, in the order scripts/fuzz.sh runs them.
std::vector<std::string> entryNames();

}  // namespace strata::fuzz
