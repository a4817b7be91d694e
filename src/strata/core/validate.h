#pragma once
// Checks the configs' validate() share. Errors: InputError naming the config and the field.
// Thread safety: all functions are thread safe.

namespace strata {

/// Throws InputError "<config>.<field> must be finite and > 0, not <value>" unless `value` is
/// finite and positive: the check every config's validate() makes of its sizes and weights.
void requirePositive(double value, const char* config, const char* field);

}  // namespace strata
