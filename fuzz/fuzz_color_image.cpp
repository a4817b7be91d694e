// libFuzzer target: PNG and JPEG colour images, through the fuzz_color_image entry of parser_entries.h.
#include "parser_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const strata::fuzz::Entry kEntry = strata::fuzz::findEntry("fuzz_color_image");
  return strata::fuzz::refuseOrAccept(kEntry, data, size);
}
