#include "strata/mesh/mesh_file_limits.h"

#include "strata/core/error.h"

namespace strata {

void checkMeshCount(std::size_t count, std::size_t limit, const char* limit_name,
                    const char* what) {
  if (count <= limit) return;
  throw InputError(std::string(what) + " count " + std::to_string(count) + " is over " +
                   limit_name + " = " + std::to_string(limit));
}

}  // namespace strata
