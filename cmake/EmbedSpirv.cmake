# Writes a C++ source holding the SPIR-V words of SPV as kSpirv_<STEM>.
file(READ "${SPV}" hex HEX)
string(LENGTH "${hex}" hex_len)
math(EXPR word_count "${hex_len} / 8")
# SPIR-V is little-endian on every host we support: bytes b0 b1 b2 b3 -> 0xb3b2b1b0.
string(REGEX REPLACE "([0-9a-f][0-9a-f])([0-9a-f][0-9a-f])([0-9a-f][0-9a-f])([0-9a-f][0-9a-f])"
       "0x\\4\\3\\2\\1u," words "${hex}")
file(WRITE "${OUT}.tmp" "// Generated from ${STEM}.comp. Do not edit.\n#include <cstddef>\n#include <cstdint>\nnamespace strata::shaders {\nextern const std::uint32_t kSpirv_${STEM}[];\nextern const std::size_t kSpirvWords_${STEM};\nconst std::uint32_t kSpirv_${STEM}[] = {${words}};\nconst std::size_t kSpirvWords_${STEM} = ${word_count};\n}\n")
file(RENAME "${OUT}.tmp" "${OUT}")
