#include "algo/camera/rectify.hpp"

#include <algorithm>
#include <cmath>

namespace petra {

namespace {

constexpr int kOne = 1 << kRemapFracBits;

// Source position -> table entry. Positions within half a pixel of the image
// are clamped onto its border pixels.
RemapEntry encode(const Eigen::Vector2d& src, int width, int height) {
  RemapEntry e;
  if (!(src.x() >= -0.5 && src.x() <= width - 0.5 && src.y() >= -0.5 && src.y() <= height - 0.5)) {
    e.x_q4 = kRemapOutside;
    return e;
  }
  const long max_x = static_cast<long>(width - 1) * kOne;
  const long max_y = static_cast<long>(height - 1) * kOne;
  const long qx = std::clamp(std::lround(src.x() * kOne), 0L, max_x);
  const long qy = std::clamp(std::lround(src.y() * kOne), 0L, max_y);
  e.x_q4 = static_cast<std::int16_t>(qx);
  e.y_q4 = static_cast<std::int16_t>(qy);
  return e;
}

Status check_image(const char* what, ImageView<const std::uint8_t> img, int width, int height) {
  if (img.width() != width || img.height() != height)
    return Error::make(Errc::invalid_argument, "rectify: %s image is %dx%d, calibration is %dx%d",
                       what, img.width(), img.height(), width, height);
  return ok_status();
}

}  // namespace

Result<Rectifier> Rectifier::create(const StereoRig& rig, std::span<RemapEntry> left_table,
                                    std::span<RemapEntry> right_table) {
  PETRA_TRY(validate(rig.left, "left"));
  PETRA_TRY(validate(rig.right, "right"));
  const int w = rig.left.width;
  const int h = rig.left.height;
  if (rig.right.width != w || rig.right.height != h)
    return Error::make(Errc::invalid_argument, "rectify: left is %dx%d but right is %dx%d", w, h,
                       rig.right.width, rig.right.height);
  if (w > kRemapMaxSide || h > kRemapMaxSide)
    return Error::make(Errc::capacity_exceeded, "rectify: %dx%d exceeds the table limit %d px", w,
                       h, kRemapMaxSide);
  const std::size_t n = table_entries(w, h);
  if (left_table.size() < n || right_table.size() < n)
    return Error::make(Errc::capacity_exceeded,
                       "rectify: tables need %zu entries each, got %zu and %zu", n,
                       left_table.size(), right_table.size());
  auto geometry = rectify_geometry(rig, w, h);
  if (!geometry) return geometry.error();

  Rectifier r;
  r.rig_ = rig;
  r.pair_ = *geometry;
  r.width_ = w;
  r.height_ = h;
  for (int side = 0; side < 2; ++side) {
    const TsaiCamera& cam = side == 0 ? rig.left : rig.right;
    const RectifiedCamera& rc = side == 0 ? r.pair_.left : r.pair_.right;
    std::span<RemapEntry> table = side == 0 ? left_table : right_table;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        auto src = rectified_to_original(cam, rc, {x, y});
        RemapEntry e;
        e.x_q4 = kRemapOutside;
        if (src) e = encode(*src, w, h);
        table[static_cast<std::size_t>(y) * w + x] = e;
      }
    }
  }
  r.left_ = left_table.first(n);
  r.right_ = right_table.first(n);
  return r;
}

namespace {

// Bilinear sample of `src` at the table entry's Q4 position (weights sum to
// 256: one rounding shift, no division). The second column (row) is read
// only when its weight is non-zero, so the last column and row of the image
// need no margin.
std::uint8_t remap_sample(const std::uint8_t* src, std::ptrdiff_t stride, RemapEntry m) {
  if (m.x_q4 == kRemapOutside) return kRectifyFill;
  const int fx = m.x_q4 & (kOne - 1);
  const int fy = m.y_q4 & (kOne - 1);
  const std::uint8_t* p = src + (m.y_q4 >> kRemapFracBits) * stride + (m.x_q4 >> kRemapFracBits);
  const int dx = (fx + kOne - 1) >> kRemapFracBits;
  const std::ptrdiff_t dy = stride * ((fy + kOne - 1) >> kRemapFracBits);
  const int top = p[0] * (kOne - fx) + p[dx] * fx;
  const int bottom = p[dy] * (kOne - fx) + p[dy + dx] * fx;
  return static_cast<std::uint8_t>((top * (kOne - fy) + bottom * fy + 128) >> 8);
}

// The entry between two table rows' entries, weight w / 16 on `b`; outside
// when either is.
RemapEntry between(RemapEntry a, RemapEntry b, int w) {
  if (a.x_q4 == kRemapOutside || b.x_q4 == kRemapOutside) return RemapEntry{kRemapOutside, 0};
  auto mix = [w](int u, int v) {
    return static_cast<std::int16_t>((u * (kOne - w) + v * w + kOne / 2) >> kRemapFracBits);
  };
  return RemapEntry{mix(a.x_q4, b.x_q4), mix(a.y_q4, b.y_q4)};
}

}  // namespace

Status Rectifier::check_rectify(ConstGray8View original, Gray8View rectified, Rect region) const {
  if (width_ == 0) return Error::make(Errc::not_ready, "rectify: rectifier not initialised");
  PETRA_TRY(check_image("original", original, width_, height_));
  PETRA_TRY(check_image("rectified", rectified, width_, height_));
  if (!region.inside(width_, height_))
    return Error::make(Errc::out_of_range, "rectify: region (%d,%d %dx%d) outside the %dx%d image",
                       region.x, region.y, region.w, region.h, width_, height_);
  return ok_status();
}

Status Rectifier::rectify(StereoSide side, ConstGray8View original, Gray8View rectified,
                          Rect region) const {
  PETRA_TRY(check_rectify(original, rectified, region));
  const std::span<const RemapEntry> t = table(side);
  for (int y = region.y; y < region.y + region.h; ++y) {
    const RemapEntry* e = t.data() + static_cast<std::size_t>(y) * width_;
    std::uint8_t* out = rectified.row(y);
    for (int x = region.x; x < region.x + region.w; ++x)
      out[x] = remap_sample(original.data(), original.stride(), e[x]);
  }
  return ok_status();
}

Status Rectifier::rectify_rows_moved(StereoSide side, ConstGray8View original, Gray8View rectified,
                                     Rect region, int rows_q4) const {
  PETRA_TRY(check_rectify(original, rectified, region));
  const std::span<const RemapEntry> t = table(side);
  const int whole = rows_q4 >> kRemapFracBits, w = rows_q4 & (kOne - 1);  // floor, fraction
  for (int y = region.y; y < region.y + region.h; ++y) {
    std::uint8_t* out = rectified.row(y);
    const int ya = y + whole, yb = ya + (w > 0 ? 1 : 0);
    if (ya < 0 || yb >= height_) {  // no table row there: nothing to sample
      std::fill(out + region.x, out + region.x + region.w, kRectifyFill);
      continue;
    }
    const RemapEntry* a = t.data() + static_cast<std::size_t>(ya) * width_;
    const RemapEntry* b = t.data() + static_cast<std::size_t>(yb) * width_;
    for (int x = region.x; x < region.x + region.w; ++x)
      out[x] = remap_sample(original.data(), original.stride(), between(a[x], b[x], w));
  }
  return ok_status();
}

Status Rectifier::rectify(StereoSide side, ConstGray8View original, Gray8View rectified) const {
  return rectify(side, original, rectified, Rect{0, 0, width_, height_});
}

Result<Eigen::Vector2d> Rectifier::to_rectified(StereoSide side, const Eigen::Vector2d& px) const {
  if (width_ == 0) return Error::make(Errc::not_ready, "rectify: rectifier not initialised");
  return original_to_rectified(camera(side), rect(side), px);
}

Result<Eigen::Vector2d> Rectifier::to_original(StereoSide side, const Eigen::Vector2d& px) const {
  if (width_ == 0) return Error::make(Errc::not_ready, "rectify: rectifier not initialised");
  return rectified_to_original(camera(side), rect(side), px);
}

namespace {

// Bounding box of a rectangle's outline mapped through `map`, as pixel
// indices clipped to the image.
template <class Map>
Result<Rect> map_outline(Rect r, int width, int height, Map map) {
  if (r.empty())
    return Error::make(Errc::invalid_argument, "rectify: ROI %dx%d is empty", r.w, r.h);
  if (!r.inside(width, height))
    return Error::make(Errc::out_of_range, "rectify: ROI (%d,%d %dx%d) is outside the %dx%d image",
                       r.x, r.y, r.w, r.h, width, height);
  double u0 = 1e300, v0 = 1e300, u1 = -1e300, v1 = -1e300;
  // About one sample per pixel of outline, at most 64 per side: the mapping
  // is smooth, so the box is exact to a fraction of a pixel.
  const int nx = std::clamp(r.w, 1, 64);
  const int ny = std::clamp(r.h, 1, 64);
  auto visit = [&](double u, double v) -> Status {
    auto m = map(Eigen::Vector2d(u, v));
    if (!m) return m.error();
    u0 = std::min(u0, m->x());
    u1 = std::max(u1, m->x());
    v0 = std::min(v0, m->y());
    v1 = std::max(v1, m->y());
    return ok_status();
  };
  const double xa = r.x, xb = r.x + r.w - 1, ya = r.y, yb = r.y + r.h - 1;
  for (int i = 0; i <= nx; ++i) {
    const double u = xa + (xb - xa) * i / nx;
    PETRA_TRY(visit(u, ya));
    PETRA_TRY(visit(u, yb));
  }
  for (int i = 0; i <= ny; ++i) {
    const double v = ya + (yb - ya) * i / ny;
    PETRA_TRY(visit(xa, v));
    PETRA_TRY(visit(xb, v));
  }
  const int x0 = std::max(0, static_cast<int>(std::floor(u0)));
  const int y0 = std::max(0, static_cast<int>(std::floor(v0)));
  const int x1 = std::min(width - 1, static_cast<int>(std::ceil(u1)));
  const int y1 = std::min(height - 1, static_cast<int>(std::ceil(v1)));
  if (!(u1 >= 0 && v1 >= 0 && u0 <= width - 1 && v0 <= height - 1) || x1 < x0 || y1 < y0)
    return Error::make(Errc::out_of_range, "rectify: ROI (%d,%d %dx%d) maps outside the image", r.x,
                       r.y, r.w, r.h);
  return Rect{x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

}  // namespace

Result<Rect> Rectifier::roi_to_rectified(StereoSide side, Rect roi) const {
  if (width_ == 0) return Error::make(Errc::not_ready, "rectify: rectifier not initialised");
  return petra::roi_to_rectified(camera(side), rect(side), roi, width_, height_);
}

Result<Rect> roi_to_rectified(const TsaiCamera& cam, const RectifiedCamera& rect, Rect roi,
                              int width, int height) {
  return map_outline(roi, width, height,
                     [&](const Eigen::Vector2d& p) { return original_to_rectified(cam, rect, p); });
}

Result<Rect> Rectifier::roi_to_original(StereoSide side, Rect roi) const {
  if (width_ == 0) return Error::make(Errc::not_ready, "rectify: rectifier not initialised");
  return map_outline(roi, width_, height_,
                     [&](const Eigen::Vector2d& p) { return to_original(side, p); });
}

}  // namespace petra
