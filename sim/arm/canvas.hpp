// A 2-D drawing surface for ground pictures: lines, filled polygons, discs and
// text, in pixel coordinates (x right, y down). Two backends draw the same
// calls: RasterCanvas into an RGB image (anti-aliased; text from a built-in
// 5x7 font, upper case) for PNG, SvgCanvas into SVG text.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "sim/io/image_io.hpp"

namespace petra::sim {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

class Canvas {
 public:
  virtual ~Canvas() = default;
  virtual int width() const = 0;
  virtual int height() const = 0;
  virtual void line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Rgb color, double width_px,
                    double opacity = 1.0) = 0;
  virtual void polygon(std::span<const Eigen::Vector2d> points, Rgb fill, double opacity) = 0;
  virtual void disc(const Eigen::Vector2d& centre, double radius_px, Rgb fill,
                    double opacity = 1.0) = 0;
  // Top-left of the text at `at`; `scale` multiplies the 5x7 cell (raster) or
  // sets the font size to 9 * scale px (SVG).
  virtual void text(const Eigen::Vector2d& at, std::string_view s, Rgb color, int scale = 2) = 0;
  virtual void rect(double x, double y, double w, double h, Rgb fill, double opacity = 1.0);
  // Drawing between begin_clip and end_clip stays inside the rectangle.
  virtual void begin_clip(double x, double y, double w, double h) = 0;
  virtual void end_clip() = 0;
};

class RasterCanvas final : public Canvas {
 public:
  RasterCanvas(int width, int height, Rgb background);
  int width() const override { return image_.width; }
  int height() const override { return image_.height; }
  void line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Rgb color, double width_px,
            double opacity = 1.0) override;
  void polygon(std::span<const Eigen::Vector2d> points, Rgb fill, double opacity) override;
  void disc(const Eigen::Vector2d& centre, double radius_px, Rgb fill,
            double opacity = 1.0) override;
  void text(const Eigen::Vector2d& at, std::string_view s, Rgb color, int scale = 2) override;
  void rect(double x, double y, double w, double h, Rgb fill, double opacity = 1.0) override;
  void begin_clip(double x, double y, double w, double h) override;
  void end_clip() override;
  const io::RgbImage& image() const { return image_; }

 private:
  void blend(int x, int y, Rgb c, double alpha);
  io::RgbImage image_;
  int clip_x0_ = 0, clip_y0_ = 0, clip_x1_ = 1 << 30, clip_y1_ = 1 << 30;
};

class SvgCanvas final : public Canvas {
 public:
  SvgCanvas(int width, int height, Rgb background);
  int width() const override { return width_; }
  int height() const override { return height_; }
  void line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Rgb color, double width_px,
            double opacity = 1.0) override;
  void polygon(std::span<const Eigen::Vector2d> points, Rgb fill, double opacity) override;
  void disc(const Eigen::Vector2d& centre, double radius_px, Rgb fill,
            double opacity = 1.0) override;
  void text(const Eigen::Vector2d& at, std::string_view s, Rgb color, int scale = 2) override;
  void begin_clip(double x, double y, double w, double h) override;
  void end_clip() override;
  std::string finish() const { return body_ + "</svg>\n"; }

 private:
  int width_, height_;
  std::string body_;
  int clips_ = 0;
};

}  // namespace petra::sim
