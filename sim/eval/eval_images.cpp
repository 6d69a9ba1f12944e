#include "sim/eval/eval_images.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "algo/chain/products.hpp"
#include "sim/eval/tiny_font.hpp"

namespace petra::eval {

namespace {

constexpr Colour kWhite{255, 255, 255}, kBlack{0, 0, 0};
constexpr Colour from(palette::Rgb8 c) {
  return {c.r, c.g, c.b};
}

// Scale so small ROIs are still readable (at least ~480 px wide).
int picture_scale(int w) {
  return std::clamp((480 + w - 1) / std::max(w, 1), 1, 4);
}

// The ROI-sized RGB picture `src` (3 * w x h) into img, each pixel an s x s block.
void blit_scaled(const io::RgbImage& src, int s, io::RgbImage& img) {
  for (int y = 0; y < src.height; ++y)
    for (int x = 0; x < src.width; ++x) {
      const std::uint8_t* p = src.at(x, y);
      fill_rect(img, x * s, y * s, s, s, Colour{p[0], p[1], p[2]});
    }
}

ImageView<std::uint8_t> rgb_view(io::RgbImage& img) {
  return ImageView<std::uint8_t>(img.at(0, 0), 3 * img.width, img.height);
}

void label(io::RgbImage& img, int x, int y, const char* text, int scale) {
  draw_text(img, x + 1, y + 1, text, kBlack, scale);
  draw_text(img, x, y, text, kWhite, scale);
}

}  // namespace

io::RgbImage disparity_picture(ConstDisparityMap map) {
  const int w = map.q4.width(), h = map.q4.height(), s = picture_scale(w);
  io::RgbImage base(w, h);
  (void)products::disparity_rgb(map, rgb_view(base));  // sized here: cannot fail
  const products::DisparitySpan span = products::disparity_span(map);
  const double lo = disparity_px(span.lo_q4), hi = disparity_px(span.hi_q4);
  const int bar = 30;
  io::RgbImage img(w * s, h * s + bar);
  blit_scaled(base, s, img);
  fill_rect(img, 0, h * s, w * s, bar, {40, 40, 40});
  for (int x = 0; x < w * s; ++x)
    fill_rect(img, x, h * s + 4, 1, 10,
              from(palette::disparity_colour(static_cast<double>(x) / (w * s - 1))));
  char text[64];
  std::snprintf(text, sizeof text, "%.1f PX", lo);
  draw_text(img, 2, h * s + 17, text, kWhite);
  std::snprintf(text, sizeof text, "%.1f PX", hi);
  draw_text(img, w * s - text_width(text) - 2, h * s + 17, text, kWhite);
  if (!span.any) draw_text(img, 4, 4, "NO MATCHES", kWhite, 2);
  return img;
}

io::RgbImage overlay_picture(const PipelineOutput& out, const RectifiedPair& pair) {
  const Rect roi = out.roi_rectified;
  const int s = picture_scale(roi.w);
  const ReconstructionOutput& r = out.result;
  const int accepted = r.planes.accepted;
  io::RgbImage base(roi.w, roi.h);
  (void)products::overlay_classes(out, rgb_view(base));  // sized here: cannot fail
  const int legend_h = 14 * 2 + 8;
  io::RgbImage img(roi.w * s, roi.h * s + legend_h);
  blit_scaled(base, s, img);
  // Plane markers: rank at the centroid, a stroke along the normal.
  for (int k = 0; k < accepted; ++k) {
    const GrindPlane& p = r.planes.planes[k];
    auto c = rectified_project(pair, p.centroid_mm);
    auto tip = rectified_project(pair, p.centroid_mm + 25.0 * p.normal);
    if (!c || !tip) continue;
    const int cx = static_cast<int>(std::lround((c->uv_left.x() - roi.x) * s));
    const int cy = static_cast<int>(std::lround((c->uv_left.y() - roi.y) * s));
    const int tx = static_cast<int>(std::lround((tip->uv_left.x() - roi.x) * s));
    const int ty = static_cast<int>(std::lround((tip->uv_left.y() - roi.y) * s));
    draw_line(img, cx, cy, tx, ty, kBlack, 4);
    draw_line(img, cx, cy, tx, ty, kWhite, 2);
    draw_disc(img, cx, cy, 4 + s, kBlack);
    draw_disc(img, cx, cy, 2 + s, from(palette::plane_colour(k)));
    char num[16];
    std::snprintf(num, sizeof num, "%d", k + 1);
    label(img, cx + 6 + s, cy - 7, num, 2);
  }
  if (out.click_rectified.present) {
    const int cx = (out.click_rectified.u - roi.x) * s + s / 2,
              cy = (out.click_rectified.v - roi.y) * s + s / 2;
    draw_line(img, cx - 8, cy, cx + 8, cy, kBlack, 3);
    draw_line(img, cx, cy - 8, cx, cy + 8, kBlack, 3);
    draw_line(img, cx - 7, cy, cx + 7, cy, kWhite, 1);
    draw_line(img, cx, cy - 7, cx, cy + 7, kWhite, 1);
  }
  // Legend: the classes algo/chain/products tints (rock and refused candidates are as seen).
  const int ly = roi.h * s;
  fill_rect(img, 0, ly, img.width, legend_h, {30, 30, 30});
  int x = 4;
  auto entry = [&](Colour c, const char* text, int row) {
    const int y = ly + 4 + row * 16;
    if (x + 14 + text_width(text) > img.width && row == 0) return false;
    fill_rect(img, x, y, 10, 10, c);
    x = draw_text(img, x + 14, y + 2, text, kWhite) + 8;
    return true;
  };
  entry(from(palette::kGround), "GROUND", 0);
  entry(from(palette::kShadow), "SHADOW", 0);
  x = 4;
  for (int k = 0; k < accepted; ++k) {
    char text[32];
    std::snprintf(text, sizeof text, "PLANE %d", k + 1);
    entry(from(palette::plane_colour(k)), text, 1);
  }
  if (accepted == 0) draw_text(img, 4, ly + 22, "NO GRIND PLANE", kWhite);
  return img;
}

}  // namespace petra::eval
