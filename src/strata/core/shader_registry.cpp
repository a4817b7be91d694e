#include "strata/core/shader_registry.h"

#include "strata/core/error.h"

namespace strata::shaders {

const ShaderEntry& spirv(const std::string& name) {
  for (const ShaderEntry& entry : all()) {
    if (name == entry.name) {
      if (entry.word_count < 5 || entry.words[0] != 0x07230203u) {
        throw Error("shader '" + name + "' is embedded but is not valid SPIR-V (bad magic number); "
                    "rebuild the project so glslangValidator regenerates it");
      }
      return entry;
    }
  }
  throw Error("shader '" + name + "' is not embedded in this build; add shaders/" + name +
              ".comp to shaders/CMakeLists.txt");
}

}  // namespace strata::shaders
