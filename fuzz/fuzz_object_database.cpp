// libFuzzer target: object database files (deserializeObjectDatabase), through the
// fuzz_object_database entry of parser_entries.h.
#include "parser_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const strata::fuzz::Entry kEntry = strata::fuzz::findEntry("fuzz_object_database");
  return strata::fuzz::refuseOrAccept(kEntry, data, size);
}
