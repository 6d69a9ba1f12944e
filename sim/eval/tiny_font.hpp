// A 5x7 bitmap font (digits, upper-case letters, a few signs) for labels on
// the ground tool's pictures; unknown characters draw as blanks.
#pragma once

#include <string_view>

#include "sim/io/image_io.hpp"

namespace petra::eval {

struct Colour {
  std::uint8_t r, g, b;
};

// Draws text with its top-left corner at (x, y), each font pixel `scale`
// image pixels; clipped to the image. Returns the x after the text.
int draw_text(io::RgbImage& img, int x, int y, std::string_view text, Colour c, int scale = 1);
int text_width(std::string_view text, int scale = 1);

void fill_rect(io::RgbImage& img, int x, int y, int w, int h, Colour c);
void draw_line(io::RgbImage& img, int x0, int y0, int x1, int y1, Colour c, int thickness = 1);
void draw_disc(io::RgbImage& img, int cx, int cy, int radius, Colour c);

}  // namespace petra::eval
