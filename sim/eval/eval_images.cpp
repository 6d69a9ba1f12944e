#include "sim/eval/eval_images.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "sim/eval/ply_writer.hpp"
#include "sim/eval/tiny_font.hpp"
#include "tlm/palette.hpp"

namespace petra::eval {

namespace {

constexpr Colour kWhite{255, 255, 255}, kBlack{0, 0, 0};
constexpr Colour from(palette::Rgb8 c) {
  return {c.r, c.g, c.b};
}
constexpr Colour kShadowTint = from(palette::kShadow), kRejectedTint = from(palette::kRejected);

// Scale so small ROIs are still readable (at least ~480 px wide).
int picture_scale(int w) {
  return std::clamp((480 + w - 1) / std::max(w, 1), 1, 4);
}

// Blue (far) -> cyan -> green -> yellow -> red (near): tlm/palette.hpp.
Colour ramp(double t) {
  return from(palette::disparity_colour(t));
}

Colour blend(std::uint8_t gray, Colour tint, double alpha) {
  auto mix = [&](std::uint8_t t) {
    return static_cast<std::uint8_t>(std::lround((1 - alpha) * gray + alpha * t));
  };
  return {mix(tint.r), mix(tint.g), mix(tint.b)};
}

Colour to_colour(Rgb c) {
  return {c.r, c.g, c.b};
}

void label(io::RgbImage& img, int x, int y, const char* text, int scale) {
  draw_text(img, x + 1, y + 1, text, kBlack, scale);
  draw_text(img, x, y, text, kWhite, scale);
}

}  // namespace

io::RgbImage disparity_picture(ConstDisparityMap map) {
  const int w = map.q4.width(), h = map.q4.height(), s = picture_scale(w);
  double lo = 0, hi = 0;
  bool any = false;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (is_valid_disparity(map.q4(x, y))) {
        const double d = disparity_px(map.q4(x, y));
        lo = any ? std::min(lo, d) : d;
        hi = any ? std::max(hi, d) : d;
        any = true;
      }
  const int bar = 30;
  io::RgbImage img(w * s, h * s + bar);
  for (int y = 0; y < h * s; ++y)
    for (int x = 0; x < w * s; ++x) {
      const std::int16_t q = map.q4(x / s, y / s);
      const Colour c =
          is_valid_disparity(q) ? ramp((disparity_px(q) - lo) / std::max(hi - lo, 1e-9)) : kBlack;
      std::uint8_t* p = img.at(x, y);
      p[0] = c.r;
      p[1] = c.g;
      p[2] = c.b;
    }
  fill_rect(img, 0, h * s, w * s, bar, {40, 40, 40});
  for (int x = 0; x < w * s; ++x)
    fill_rect(img, x, h * s + 4, 1, 10, ramp(static_cast<double>(x) / (w * s - 1)));
  char text[64];
  std::snprintf(text, sizeof text, "%.1f PX", lo);
  draw_text(img, 2, h * s + 17, text, kWhite);
  std::snprintf(text, sizeof text, "%.1f PX", hi);
  draw_text(img, w * s - text_width(text) - 2, h * s + 17, text, kWhite);
  if (!any) draw_text(img, 4, 4, "NO MATCHES", kWhite, 2);
  return img;
}

io::RgbImage overlay_picture(const PipelineOutput& out, const RectifiedPair& pair) {
  const Rect roi = out.roi_rectified;
  const int s = picture_scale(roi.w);
  const ReconstructionOutput& r = out.result;
  const int accepted = r.planes.accepted;
  // Class of each ROI pixel from its 3-D point (255: no point).
  std::vector<std::uint8_t> cls(static_cast<std::size_t>(roi.w) * roi.h, 255);
  for (std::size_t i = 0; i < r.pixels.size(); ++i) {
    const int x = r.pixels[i].u - roi.x, y = r.pixels[i].v - roi.y;
    if (x >= 0 && y >= 0 && x < roi.w && y < roi.h)
      cls[static_cast<std::size_t>(y) * roi.w + x] = r.vertex_class[i];
  }
  const int legend_h = 14 * 2 + 8;
  io::RgbImage img(roi.w * s, roi.h * s + legend_h);
  for (int y = 0; y < roi.h; ++y)
    for (int x = 0; x < roi.w; ++x) {
      const std::uint8_t g = out.left_rectified(roi.x + x, roi.y + y);
      const std::uint8_t c = cls[static_cast<std::size_t>(y) * roi.w + x];
      Colour col{g, g, g};
      if (c == 255) {
        if (out.left_shadow.is_shadow(roi.x + x, roi.y + y)) col = blend(g, kShadowTint, 0.5);
      } else if (c >= kVertexPlane0 && c - kVertexPlane0 >= accepted) {
        col = blend(g, kRejectedTint, 0.6);
      } else {
        col = blend(g, to_colour(class_colour(c)), c >= kVertexPlane0 ? 0.6 : 0.35);
      }
      fill_rect(img, x * s, y * s, s, s, col);
    }
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
    draw_disc(img, cx, cy, 2 + s,
              to_colour(class_colour(static_cast<std::uint8_t>(kVertexPlane0 + k))));
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
  // Legend.
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
  entry(to_colour(class_colour(kVertexGround)), "GROUND", 0);
  entry(to_colour(class_colour(kVertexRock)), "ROCK", 0);
  entry(kShadowTint, "SHADOW", 0);
  if (r.planes.count > accepted) entry(kRejectedTint, "REJECTED", 0);
  x = 4;
  for (int k = 0; k < accepted; ++k) {
    char text[32];
    std::snprintf(text, sizeof text, "PLANE %d", k + 1);
    entry(to_colour(class_colour(static_cast<std::uint8_t>(kVertexPlane0 + k))), text, 1);
  }
  if (accepted == 0) draw_text(img, 4, ly + 22, "NO GRIND PLANE", kWhite);
  return img;
}

}  // namespace petra::eval
