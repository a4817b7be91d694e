#pragma once
// A tiny built-in 5x7 bitmap font for labels on generated pictures (no font files needed):
// digits, upper-case letters (lower case is drawn upper case) and . , - + = : / % ( ) _ and space;
// any other character draws as a hollow box.
#include <array>
#include <cstdint>
#include <string>

#include "strata/core/types.h"

namespace strata::apps {

using Rgb = std::array<std::uint8_t, 3>;

inline constexpr int kGlyphWidth = 5;
inline constexpr int kGlyphHeight = 7;
inline constexpr int kGlyphAdvance = 6;  // one blank column between characters

/// Width in pixels of `text` drawn at `scale` pixels per font pixel.
int textWidth(const std::string& text, int scale);

/// Draws `text` with its top-left corner at (x, y); clipped to the image.
void drawText(ColorImage& image, int x, int y, const std::string& text, int scale, Rgb colour);

}  // namespace strata::apps
