// libFuzzer target: EuRoC data.csv (camera, IMU or ground truth), through the fuzz_euroc_csv entry
// of parser_entries.h.
#include "parser_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const strata::fuzz::Entry kEntry = strata::fuzz::findEntry("fuzz_euroc_csv");
  return strata::fuzz::refuseOrAccept(kEntry, data, size);
}
