#pragma once
// SPIR-V of every shader in shaders/, embedded at build time (cmake/StrataShaders.cmake).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace strata::shaders {

struct ShaderEntry {
  const char* name;  // file stem of the .comp source
  const std::uint32_t* words;
  std::size_t word_count;
};

/// Every embedded shader (generated).
const std::vector<ShaderEntry>& all();

/// The SPIR-V of shader `name`; throws strata::Error naming the shader if it is not embedded.
const ShaderEntry& spirv(const std::string& name);

}  // namespace strata::shaders
