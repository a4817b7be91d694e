// libFuzzer target: map files of both versions (deserializeMapFile), through the fuzz_map_file
// entry of parser_entries.h.
#include "parser_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const strata::fuzz::Entry kEntry = strata::fuzz::findEntry("fuzz_map_file");
  return strata::fuzz::refuseOrAccept(kEntry, data, size);
}
