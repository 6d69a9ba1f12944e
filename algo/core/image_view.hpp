// ImageView<T>: a non-owning, strided 2-D view over caller-owned pixels.
// Stride is in elements, so a sub-view (ROI) shares the parent's memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/core/assert.hpp"

namespace petra {

// Axis-aligned rectangle in pixels: x, y top-left; w, h size.
struct Rect {
  int x = 0;
  int y = 0;
  int w = 0;
  int h = 0;

  constexpr bool empty() const { return w <= 0 || h <= 0; }
  constexpr long area() const { return empty() ? 0 : static_cast<long>(w) * h; }
  constexpr bool contains(int px, int py) const {
    return px >= x && py >= y && px < x + w && py < y + h;
  }
  constexpr bool inside(int width, int height) const {
    return !empty() && x >= 0 && y >= 0 && x + w <= width && y + h <= height;
  }
  friend constexpr bool operator==(const Rect&, const Rect&) = default;
};

template <class T>
class ImageView {
 public:
  using value_type = T;

  constexpr ImageView() = default;
  constexpr ImageView(T* data, int width, int height, std::ptrdiff_t stride)
      : data_(data), width_(width), height_(height), stride_(stride) {
    PETRA_ASSERT(width >= 0 && height >= 0 && stride >= width);
  }
  constexpr ImageView(T* data, int width, int height) : ImageView(data, width, height, width) {}

  // A view over a span that must hold at least width*height elements.
  static ImageView over(std::span<T> pixels, int width, int height) {
    PETRA_ASSERT(pixels.size() >=
                 static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    return ImageView(pixels.data(), width, height, width);
  }

  // Implicit conversion to a read-only view.
  constexpr operator ImageView<const T>() const {  // NOLINT(google-explicit-constructor)
    return ImageView<const T>(data_, width_, height_, stride_);
  }

  constexpr int width() const { return width_; }
  constexpr int height() const { return height_; }
  constexpr std::ptrdiff_t stride() const { return stride_; }
  constexpr bool empty() const { return width_ == 0 || height_ == 0; }
  constexpr T* data() const { return data_; }

  constexpr T* row(int y) const { return data_ + y * stride_; }
  constexpr T& operator()(int x, int y) const { return data_[y * stride_ + x]; }
  T& at(int x, int y) const {
    PETRA_ASSERT(x >= 0 && y >= 0 && x < width_ && y < height_);
    return (*this)(x, y);
  }
  constexpr bool in_bounds(int x, int y) const {
    return x >= 0 && y >= 0 && x < width_ && y < height_;
  }

  // Sub-view of a rectangle that lies inside this view.
  ImageView sub(const Rect& r) const {
    PETRA_ASSERT(r.inside(width_, height_) || (r.w == 0 || r.h == 0));
    return ImageView(data_ + r.y * stride_ + r.x, r.w, r.h, stride_);
  }

  void fill(const T& v) const {
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x) row(y)[x] = v;
  }

 private:
  T* data_ = nullptr;
  int width_ = 0;
  int height_ = 0;
  std::ptrdiff_t stride_ = 0;
};

using Gray8View = ImageView<std::uint8_t>;
using ConstGray8View = ImageView<const std::uint8_t>;

// Copy pixel values between views of equal size.
template <class T, class U>
void copy_pixels(ImageView<const T> src, ImageView<U> dst) {
  PETRA_ASSERT(src.width() == dst.width() && src.height() == dst.height());
  for (int y = 0; y < src.height(); ++y) {
    const T* s = src.row(y);
    U* d = dst.row(y);
    for (int x = 0; x < src.width(); ++x) d[x] = static_cast<U>(s[x]);
  }
}

}  // namespace petra
