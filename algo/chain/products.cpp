#include "algo/chain/products.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace petra::products {

namespace {

Status check_size(const char* what, int w, int h, int want_w, int want_h) {
  if (w != want_w || h != want_h)
    return Error::make(Errc::invalid_argument, "products: %s is %dx%d, the ROI needs %dx%d", what,
                       w, h, want_w, want_h);
  return ok_status();
}

void put(std::uint8_t* px, palette::Rgb8 c) {
  px[0] = c.r;
  px[1] = c.g;
  px[2] = c.b;
}

// A class colour over the gray it covers: two parts colour, one part gray.
void tint(std::uint8_t* px, std::uint8_t gray, palette::Rgb8 c) {
  const std::uint8_t rgb[3] = {c.r, c.g, c.b};
  for (int k = 0; k < 3; ++k) px[k] = static_cast<std::uint8_t>((gray + 2 * rgb[k]) / 3);
}

}  // namespace

palette::Rgb8 class_colour(std::uint8_t c) {
  return c == kVertexGround ? palette::kGround
         : c == kVertexRock ? palette::kRock
                            : palette::plane_colour(c - kVertexPlane0);
}

DisparitySpan disparity_span(ConstDisparityMap map) {
  DisparitySpan s;
  for (int y = 0; y < map.q4.height(); ++y)
    for (int x = 0; x < map.q4.width(); ++x) {
      const std::int16_t q = map.q4(x, y);
      if (!is_valid_disparity(q)) continue;
      s.lo_q4 = s.any ? std::min(s.lo_q4, q) : q;
      s.hi_q4 = s.any ? std::max(s.hi_q4, q) : q;
      s.any = true;
    }
  return s;
}

Status disparity_gray(ConstDisparityMap map, Gray8View out) {
  const int w = map.q4.width(), h = map.q4.height();
  PETRA_TRY(check_size("disparity picture", out.width(), out.height(), w, h));
  const DisparitySpan s = disparity_span(map);
  const int span = s.hi_q4 > s.lo_q4 ? s.hi_q4 - s.lo_q4 : 1;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::int16_t q = map.q4(x, y);
      out(x, y) =
          static_cast<std::uint8_t>(is_valid_disparity(q) ? 1 + (q - s.lo_q4) * 254 / span : 0);
    }
  return ok_status();
}

Status disparity_rgb(ConstDisparityMap map, ImageView<std::uint8_t> out_rgb) {
  const int w = map.q4.width(), h = map.q4.height();
  PETRA_TRY(check_size("disparity picture", out_rgb.width(), out_rgb.height(), 3 * w, h));
  const DisparitySpan s = disparity_span(map);
  const double lo = disparity_px(s.lo_q4), hi = disparity_px(s.hi_q4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::int16_t q = map.q4(x, y);
      put(out_rgb.row(y) + 3 * x,
          is_valid_disparity(q)
              ? palette::disparity_colour((disparity_px(q) - lo) / std::max(hi - lo, 1e-9))
              : palette::kNoData);
    }
  return ok_status();
}

Status overlay_classes(const PipelineOutput& p, ImageView<std::uint8_t> out_rgb) {
  const Rect roi = p.roi_rectified;
  const int w = roi.w, h = roi.h;
  PETRA_TRY(check_size("overlay", out_rgb.width(), out_rgb.height(), 3 * w, h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::uint8_t g = p.left_rectified(roi.x + x, roi.y + y);
      std::uint8_t* o = out_rgb.row(y) + 3 * x;
      o[0] = o[1] = o[2] = g;
      if (p.left_shadow.is_shadow(roi.x + x, roi.y + y)) tint(o, g, palette::kShadow);
    }
  const ReconstructionOutput& r = p.result;
  const int accepted = r.planes.accepted;
  for (std::size_t i = 0; i < r.pixels.size() && i < r.vertex_class.size(); ++i) {
    const int x = r.pixels[i].u - roi.x, y = r.pixels[i].v - roi.y;
    if (x < 0 || y < 0 || x >= w || y >= h) continue;
    const std::uint8_t k = r.vertex_class[i];
    std::uint8_t* o = out_rgb.row(y) + 3 * x;
    const std::uint8_t g = p.left_rectified(roi.x + x, roi.y + y);
    if (k == kVertexGround)
      tint(o, g, palette::kGround);
    else if (k >= kVertexPlane0 && k - kVertexPlane0 < accepted)
      tint(o, g, class_colour(k));
  }
  return ok_status();
}

Status overlay(const PipelineOutput& p, const RectifiedPair& pair,
               ImageView<std::uint8_t> out_rgb) {
  PETRA_TRY(overlay_classes(p, out_rgb));
  const Rect roi = p.roi_rectified;
  const int w = roi.w, h = roi.h;
  auto at = [&](int x, int y) { return out_rgb.row(y) + 3 * x; };
  const ReconstructionOutput& r = p.result;
  for (int k = 0; k < r.planes.accepted; ++k) {
    auto c = rectified_project(pair, r.planes.planes[k].centroid_mm);
    if (!c) continue;
    const int cx = static_cast<int>(std::lround(c->uv_left.x())) - roi.x;
    const int cy = static_cast<int>(std::lround(c->uv_left.y())) - roi.y;
    for (int d = -6; d <= 6; ++d)
      for (int t = -1; t <= 1; ++t) {
        if (cx + d >= 0 && cx + d < w && cy + t >= 0 && cy + t < h)
          std::memset(at(cx + d, cy + t), 255, 3);
        if (cx + t >= 0 && cx + t < w && cy + d >= 0 && cy + d < h)
          std::memset(at(cx + t, cy + d), 255, 3);
      }
  }
  return ok_status();
}

}  // namespace petra::products
