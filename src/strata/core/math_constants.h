#pragma once
// Mathematical constants shared by the host and engine code (C++17 has no <numbers>).

namespace strata {

inline constexpr double kPi = 3.14159265358979323846;

}  // namespace strata
