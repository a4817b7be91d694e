// libFuzzer target: imu_t payloads, through the fuzz_lcm_imu entry of parser_entries.h.
#include "parser_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const strata::fuzz::Entry kEntry = strata::fuzz::findEntry("fuzz_lcm_imu");
  return strata::fuzz::refuseOrAccept(kEntry, data, size);
}
