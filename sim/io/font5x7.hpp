// The 5x7 bitmap font of the ground tools' pictures (digits, upper-case
// letters, common signs): one table for every picture that carries labels.
#pragma once

#include <cstdint>

namespace petra::io {

// Seven rows, top first; bit 4 is the leftmost of the five columns.
struct Glyph5x7 {
  char c;
  std::uint8_t rows[7];
};

// The glyph of `c` (lower case drawn as upper case), or nullptr when the font
// has none: each caller decides what an unknown character looks like.
const Glyph5x7* font5x7(char c);

// Advance per character in font pixels (five columns and one of spacing).
inline constexpr int kFont5x7Advance = 6;

}  // namespace petra::io
