#include "strata/core/validate.h"

#include <cmath>
#include <sstream>

#include "strata/core/error.h"

namespace strata {

void requirePositive(double value, const char* config, const char* field) {
  if (std::isfinite(value) && value > 0.0) return;
  std::ostringstream message;
  message << config << "." << field << " must be finite and > 0, not " << value;
  throw InputError(message.str());
}

}  // namespace strata
