#pragma once
// Checks of the commands' options. finiteNumber() for the parser: CLI::Range lets NaN through
// (every comparison with it is false), so options that take a real number get it. The require*
// functions for runX(), which tests call without the parser: InputError naming the option, the
// accepted range in plain numbers and the value given.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <string>

#include "strata/core/error.h"

namespace strata::apps {

/// A finite number (not NaN, not +-inf); the message names the value.
inline CLI::Validator finiteNumber() {
  return CLI::Validator(
      [](std::string& input) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(input, value) || !std::isfinite(value)) {
          return "Value " + input + " is not a finite number";
        }
        return std::string();
      },
      "FINITE", "FINITE");
}

/// Parses the command line. Returns false when the program should exit at once with
/// `*exit_code`: 0 after --help, 2 for an option the parser refuses (its message printed), so a
/// bad option exits as every other bad input does rather than with CLI11's own codes (105, 106..).
inline bool parseCommandLine(CLI::App& app, int argc, char** argv, int* exit_code) {
  try {
    app.parse(argc, argv);
    return true;
  } catch (const CLI::ParseError& e) {
    *exit_code = app.exit(e) == 0 ? 0 : 2;
    return false;
  }
}

/// `value` finite and above `min` (at least `min` with `inclusive`), else "<option> must be a
/// finite number > <min> (<unit>), not <value>".
inline void requireNumber(double value, const char* option, const char* unit, double min,
                          bool inclusive) {
  if (std::isfinite(value) && (inclusive ? value >= min : value > min)) return;
  char text[240];
  std::snprintf(text, sizeof(text), "%s must be a finite number %s %g (%s), not %g", option,
                inclusive ? ">=" : ">", min, unit, value);
  throw InputError(text);
}

/// `value` in [lo, hi], else "<option> must be <lo> to <hi> (<unit>), not <value>".
inline void requireNumberIn(double value, const char* option, const char* unit, double lo,
                            double hi) {
  if (value >= lo && value <= hi) return;  // false for NaN
  char text[240];
  std::snprintf(text, sizeof(text), "%s must be %g to %g (%s), not %g", option, lo, hi, unit,
                value);
  throw InputError(text);
}

/// A height or coordinate: any finite number (metres), else "<option> must be a finite number
/// (metres), not <value>".
inline void requireFiniteHeight(double value, const char* option) {
  if (std::isfinite(value)) return;
  throw InputError(std::string(option) + " must be a finite number (metres), not " +
                   std::to_string(value));
}

/// A count in [lo, hi], else "<option> must be <lo> to <hi>, not <value>".
inline void requireCount(long long value, const char* option, long long lo, long long hi) {
  if (value >= lo && value <= hi) return;
  throw InputError(std::string(option) + " must be " + std::to_string(lo) + " to " +
                   std::to_string(hi) + ", not " + std::to_string(value));
}

}  // namespace strata::apps
