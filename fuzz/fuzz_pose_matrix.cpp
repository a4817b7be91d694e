// libFuzzer target: 7-Scenes frame-*.pose.txt, through the fuzz_pose_matrix entry of parser_entries.h.
#include "parser_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const strata::fuzz::Entry kEntry = strata::fuzz::findEntry("fuzz_pose_matrix");
  return strata::fuzz::refuseOrAccept(kEntry, data, size);
}
