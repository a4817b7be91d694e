#include "core/dataset.h"

namespace strata {

Dataset::~Dataset() = default;

}  // namespace strata
