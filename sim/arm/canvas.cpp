#include "sim/arm/canvas.hpp"

#include "sim/io/font5x7.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace petra::sim {

namespace {

// Unknown characters draw as '?', so a missing glyph shows on the picture.
const io::Glyph5x7& glyph(char c) {
  const io::Glyph5x7* g = io::font5x7(c);
  return g != nullptr ? *g : *io::font5x7('?');
}

// Pixel index of a coordinate, saturated: projections of points far outside a
// panel can be huge, and casting those to int would be undefined.
int to_pixel(double v) {
  return static_cast<int>(std::clamp(std::floor(v), -1.0e6, 1.0e6));
}

double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                        const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

std::string hex(Rgb c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c.r, c.g, c.b);
  return buf;
}

std::string escape(std::string_view s) {
  std::string out;
  for (char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}

}  // namespace

void Canvas::rect(double x, double y, double w, double h, Rgb fill, double opacity) {
  const Eigen::Vector2d pts[4] = {{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}};
  polygon(pts, fill, opacity);
}

RasterCanvas::RasterCanvas(int width, int height, Rgb bg) : image_(width, height) {
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      std::uint8_t* p = image_.at(x, y);
      p[0] = bg.r;
      p[1] = bg.g;
      p[2] = bg.b;
    }
  }
}

void RasterCanvas::blend(int x, int y, Rgb c, double alpha) {
  if (x < 0 || y < 0 || x >= image_.width || y >= image_.height || alpha <= 0.0) return;
  if (x < clip_x0_ || y < clip_y0_ || x >= clip_x1_ || y >= clip_y1_) return;
  alpha = std::min(alpha, 1.0);
  std::uint8_t* p = image_.at(x, y);
  const std::uint8_t src[3] = {c.r, c.g, c.b};
  for (int k = 0; k < 3; ++k)
    p[k] = static_cast<std::uint8_t>(std::lround(p[k] + alpha * (src[k] - p[k])));
}

void RasterCanvas::line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Rgb color,
                        double width_px, double opacity) {
  if (!a.allFinite() || !b.allFinite()) return;
  const double r = 0.5 * std::max(width_px, 0.5);
  const double pad = r + 1.5;
  const int x0 = std::max({to_pixel(std::min(a.x(), b.x()) - pad), 0, clip_x0_});
  const int x1 =
      std::min({to_pixel(std::max(a.x(), b.x()) + pad) + 1, image_.width - 1, clip_x1_ - 1});
  const int y0 = std::max({to_pixel(std::min(a.y(), b.y()) - pad), 0, clip_y0_});
  const int y1 =
      std::min({to_pixel(std::max(a.y(), b.y()) + pad) + 1, image_.height - 1, clip_y1_ - 1});
  const Eigen::Vector2d d = b - a;
  const double len = d.norm();
  for (int y = y0; y <= y1; ++y) {
    // Only the pixels of this row near the segment: its crossing +- the band.
    int xs = x0, xe = x1;
    if (std::abs(d.y()) > 1e-9) {
      const double xc = a.x() + (y - a.y()) * d.x() / d.y();
      const double half = pad * len / std::abs(d.y());
      xs = std::max(x0, to_pixel(xc - half));
      xe = std::min(x1, to_pixel(xc + half) + 1);
    }
    for (int x = xs; x <= xe; ++x) {
      const double dist = segment_distance({x, y}, a, b);
      blend(x, y, color, opacity * std::clamp(r + 0.5 - dist, 0.0, 1.0));
    }
  }
}

void RasterCanvas::polygon(std::span<const Eigen::Vector2d> pts, Rgb fill, double opacity) {
  if (pts.size() < 3) return;
  double xmin = pts[0].x(), xmax = xmin, ymin = pts[0].y(), ymax = ymin;
  for (const auto& p : pts) {
    if (!p.allFinite()) return;
    xmin = std::min(xmin, p.x());
    xmax = std::max(xmax, p.x());
    ymin = std::min(ymin, p.y());
    ymax = std::max(ymax, p.y());
  }
  // 4x4 samples per pixel for smooth edges (even-odd rule).
  const int ya = std::max({0, clip_y0_, to_pixel(ymin)});
  const int yb = std::min({image_.height - 1, clip_y1_ - 1, to_pixel(ymax) + 1});
  const int xa = std::max({0, clip_x0_, to_pixel(xmin)});
  const int xb = std::min({image_.width - 1, clip_x1_ - 1, to_pixel(xmax) + 1});
  for (int y = ya; y <= yb; ++y) {
    for (int x = xa; x <= xb; ++x) {
      int inside = 0;
      for (int sy = 0; sy < 4; ++sy) {
        for (int sx = 0; sx < 4; ++sx) {
          const double px = x - 0.375 + 0.25 * sx;
          const double py = y - 0.375 + 0.25 * sy;
          bool in = false;
          for (std::size_t i = 0, j = pts.size() - 1; i < pts.size(); j = i++) {
            const auto& pi = pts[i];
            const auto& pj = pts[j];
            if ((pi.y() > py) != (pj.y() > py) &&
                px < (pj.x() - pi.x()) * (py - pi.y()) / (pj.y() - pi.y()) + pi.x()) {
              in = !in;
            }
          }
          inside += in;
        }
      }
      blend(x, y, fill, opacity * inside / 16.0);
    }
  }
}

void RasterCanvas::disc(const Eigen::Vector2d& c, double radius, Rgb fill, double opacity) {
  if (!c.allFinite()) return;
  for (int y = to_pixel(c.y() - radius - 1); y <= to_pixel(c.y() + radius + 1); ++y) {
    for (int x = to_pixel(c.x() - radius - 1); x <= to_pixel(c.x() + radius + 1); ++x) {
      const double d = std::hypot(x - c.x(), y - c.y());
      blend(x, y, fill, opacity * std::clamp(radius + 0.5 - d, 0.0, 1.0));
    }
  }
}

void RasterCanvas::text(const Eigen::Vector2d& at, std::string_view s, Rgb color, int scale) {
  int pen = static_cast<int>(std::lround(at.x()));
  const int top = static_cast<int>(std::lround(at.y()));
  for (char c : s) {
    const io::Glyph5x7& g = glyph(c);
    for (int row = 0; row < 7; ++row) {
      for (int col = 0; col < 5; ++col) {
        if (!(g.rows[row] & (0x10 >> col))) continue;
        for (int dy = 0; dy < scale; ++dy) {
          for (int dx = 0; dx < scale; ++dx)
            blend(pen + col * scale + dx, top + row * scale + dy, color, 1.0);
        }
      }
    }
    pen += io::kFont5x7Advance * scale;
  }
}

void RasterCanvas::rect(double x, double y, double w, double h, Rgb fill, double opacity) {
  // Axis-aligned: whole pixels, no coverage sampling needed.
  for (int py = to_pixel(y); py < to_pixel(y + h); ++py) {
    for (int px = to_pixel(x); px < to_pixel(x + w); ++px) blend(px, py, fill, opacity);
  }
}

void RasterCanvas::begin_clip(double x, double y, double w, double h) {
  clip_x0_ = to_pixel(x);
  clip_y0_ = to_pixel(y);
  clip_x1_ = to_pixel(x + w) + 1;
  clip_y1_ = to_pixel(y + h) + 1;
}

void RasterCanvas::end_clip() {
  clip_x0_ = clip_y0_ = 0;
  clip_x1_ = clip_y1_ = 1 << 30;
}

void SvgCanvas::begin_clip(double x, double y, double w, double h) {
  char buf[200];
  ++clips_;
  std::snprintf(
      buf, sizeof buf,
      "<clipPath id=\"c%d\"><rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\"/></clipPath>"
      "<g clip-path=\"url(#c%d)\">\n",
      clips_, x, y, w, h, clips_);
  body_ += buf;
}

void SvgCanvas::end_clip() {
  body_ += "</g>\n";
}

SvgCanvas::SvgCanvas(int width, int height, Rgb bg) : width_(width), height_(height) {
  char head[256];
  std::snprintf(head, sizeof head,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 "
                "0 %d %d\">\n"
                "<rect width=\"100%%\" height=\"100%%\" fill=\"%s\"/>\n",
                width, height, width, height, hex(bg).c_str());
  body_ = head;
}

void SvgCanvas::line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Rgb color, double width_px,
                     double opacity) {
  if (!a.allFinite() || !b.allFinite()) return;
  char buf[256];
  std::snprintf(
      buf, sizeof buf,
      "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"%.1f\" "
      "stroke-opacity=\"%.2f\" stroke-linecap=\"round\"/>\n",
      a.x(), a.y(), b.x(), b.y(), hex(color).c_str(), width_px, opacity);
  body_ += buf;
}

void SvgCanvas::polygon(std::span<const Eigen::Vector2d> pts, Rgb fill, double opacity) {
  body_ += "<polygon points=\"";
  char buf[64];
  for (const auto& p : pts) {
    std::snprintf(buf, sizeof buf, "%.1f,%.1f ", p.x(), p.y());
    body_ += buf;
  }
  std::snprintf(buf, sizeof buf, "\" fill=\"%s\" fill-opacity=\"%.2f\"/>\n", hex(fill).c_str(),
                opacity);
  body_ += buf;
}

void SvgCanvas::disc(const Eigen::Vector2d& c, double radius, Rgb fill, double opacity) {
  char buf[160];
  std::snprintf(buf, sizeof buf,
                "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%.1f\" fill=\"%s\" fill-opacity=\"%.2f\"/>\n",
                c.x(), c.y(), radius, hex(fill).c_str(), opacity);
  body_ += buf;
}

void SvgCanvas::text(const Eigen::Vector2d& at, std::string_view s, Rgb color, int scale) {
  char buf[160];
  std::snprintf(
      buf, sizeof buf,
      "<text x=\"%.1f\" y=\"%.1f\" font-family=\"monospace\" font-size=\"%d\" fill=\"%s\">", at.x(),
      at.y() + 7.0 * scale, 9 * scale, hex(color).c_str());
  body_ += buf;
  body_ += escape(s);
  body_ += "</text>\n";
}

}  // namespace petra::sim
