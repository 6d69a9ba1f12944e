// Ground-side image and text file I/O (may allocate). Flight code never uses
// this: the file camera in hal/ has its own fixed-buffer reader.
//   read_gray_image: PGM (P2, P5; 8 or 16 bit), PPM (P3, P6) and PNG (gray,
//     gray+alpha, RGB, RGBA, palette; 8 or 16 bit). Colour becomes gray with
//     OpenCV's fixed-point BT.601 weights, so both see identical gray images.
//     JPEG (baseline and progressive, via libjpeg): gray is libjpeg's
//     luminance output, exactly what OpenCV's imread(IMREAD_GRAYSCALE) gives.
//   PFM: Middlebury convention ("Pf", little-endian scale -1, rows bottom to
//     top), invalid = +inf.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"

namespace petra::io {

struct GrayImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;

  GrayImage() = default;
  GrayImage(int w, int h, std::uint8_t fill = 0)
      : width(w), height(h), pixels(static_cast<std::size_t>(w) * h, fill) {}
  Gray8View view() { return {pixels.data(), width, height}; }
  ConstGray8View view() const { return {pixels.data(), width, height}; }
};

struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // interleaved R, G, B

  RgbImage() = default;
  RgbImage(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 0) {}
  std::uint8_t* at(int x, int y) { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
  const std::uint8_t* at(int x, int y) const {
    return &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
  }
};

struct FloatImage {
  int width = 0;
  int height = 0;
  std::vector<float> data;

  FloatImage() = default;
  FloatImage(int w, int h, float fill = 0.0f)
      : width(w), height(h), data(static_cast<std::size_t>(w) * h, fill) {}
  ImageView<float> view() { return {data.data(), width, height}; }
  ImageView<const float> view() const { return {data.data(), width, height}; }
};

// Errors name the file and the problem.
Result<GrayImage> read_gray_image(const std::string& path);
Result<RgbImage> read_rgb_image(const std::string& path);  // gray files are expanded
Status write_pgm(const std::string& path, ConstGray8View image);
Status write_png(const std::string& path, ConstGray8View image);
Status write_png(const std::string& path, const RgbImage& image);

Result<FloatImage> read_pfm(const std::string& path);
Status write_pfm(const std::string& path, ImageView<const float> image);

Result<std::string> read_text_file(const std::string& path, std::size_t max_bytes = 64u << 20);
Status write_text_file(const std::string& path, std::string_view text);
Status write_binary_file(const std::string& path, const void* data, std::size_t bytes);

// OpenCV's RGB -> gray: (4899 R + 9617 G + 1868 B + 8192) >> 14.
inline std::uint8_t rgb_to_gray(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  return static_cast<std::uint8_t>((4899u * r + 9617u * g + 1868u * b + 8192u) >> 14);
}

}  // namespace petra::io
