#include "sim/eval/tiny_font.hpp"

#include "sim/io/font5x7.hpp"

#include <cstdlib>

namespace petra::eval {

namespace {

void set(io::RgbImage& img, int x, int y, Colour c) {
  if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
  std::uint8_t* p = img.at(x, y);
  p[0] = c.r;
  p[1] = c.g;
  p[2] = c.b;
}

}  // namespace

int text_width(std::string_view text, int scale) {
  return static_cast<int>(text.size()) * io::kFont5x7Advance * scale;
}

int draw_text(io::RgbImage& img, int x, int y, std::string_view text, Colour c, int scale) {
  for (char ch : text) {
    if (const io::Glyph5x7* g = io::font5x7(ch)) {
      for (int r = 0; r < 7; ++r)
        for (int col = 0; col < 5; ++col)
          if (g->rows[r] & (0x10 >> col))
            fill_rect(img, x + col * scale, y + r * scale, scale, scale, c);
    }
    x += io::kFont5x7Advance * scale;
  }
  return x;
}

void fill_rect(io::RgbImage& img, int x, int y, int w, int h, Colour c) {
  for (int j = y; j < y + h; ++j)
    for (int i = x; i < x + w; ++i) set(img, i, j, c);
}

void draw_line(io::RgbImage& img, int x0, int y0, int x1, int y1, Colour c, int thickness) {
  // Bresenham, with a square brush.
  const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
  const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
  int err = dx + dy;
  for (int guard = 0; guard < 100000; ++guard) {
    fill_rect(img, x0 - thickness / 2, y0 - thickness / 2, thickness, thickness, c);
    if (x0 == x1 && y0 == y1) break;
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x0 += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y0 += sy;
    }
  }
}

void draw_disc(io::RgbImage& img, int cx, int cy, int radius, Colour c) {
  for (int y = -radius; y <= radius; ++y)
    for (int x = -radius; x <= radius; ++x)
      if (x * x + y * y <= radius * radius) set(img, cx + x, cy + y, c);
}

}  // namespace petra::eval
