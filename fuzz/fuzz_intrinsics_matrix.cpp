// libFuzzer target: 7-Scenes camera-intrinsics.txt, through the fuzz_intrinsics_matrix entry of parser_entries.h.
#include "parser_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const strata::fuzz::Entry kEntry = strata::fuzz::findEntry("fuzz_intrinsics_matrix");
  return strata::fuzz::refuseOrAccept(kEntry, data, size);
}
