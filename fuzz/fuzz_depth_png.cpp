// libFuzzer target: depth PNGs, through the fuzz_depth_png entry of parser_entries.h.
#include "parser_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const strata::fuzz::Entry kEntry = strata::fuzz::findEntry("fuzz_depth_png");
  return strata::fuzz::refuseOrAccept(kEntry, data, size);
}
