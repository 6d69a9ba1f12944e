#include "sim/eval/middlebury.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/eval/disparity_image.hpp"

namespace petra::eval {

namespace {

constexpr MiddleburyScene kScenes[] = {
    {"tsukuba", "middlebury/tsukuba", "scene1.row3.col3.ppm", "scene1.row3.col4.ppm",
     "truedisp.row3.col3.pgm", nullptr, 16, 15},
    {"venus", "middlebury/venus", "im2.ppm", "im6.ppm", "disp2.pgm", "disp6.pgm", 8, 19},
    {"sawtooth", "middlebury/sawtooth", "im2.ppm", "im6.ppm", "disp2.pgm", "disp6.pgm", 8, 19},
    {"map", "middlebury/map", "im0.pgm", "im1.pgm", "disp0.pgm", "disp1.pgm", 8, 29},
    {"teddy", "middlebury/teddy", "im2.png", "im6.png", "disp2.png", "disp6.png", 4, 59},
    {"cones", "middlebury/cones", "im2.png", "im6.png", "disp2.png", "disp6.png", 4, 59},
    {"Aloe", "middlebury2006/Aloe", "view1.png", "view5.png", "disp1.png", "disp5.png", 2, 111},
    {"Baby1", "middlebury2006/Baby1", "view1.png", "view5.png", "disp1.png", "disp5.png", 2, 79},
    // Real rocks (real-rocks/rocks1/PROVENANCE.txt): truth 27.5 .. 85 px.
    {"Rocks1", "real-rocks/rocks1", "view1.png", "view5.png", "disp1.png", "disp5.png", 2, 89},
};
constexpr std::size_t kMiddleburyCount = 8;  // the rest are the real-rock scenes

Result<io::FloatImage> load_gt(const std::string& path, int scale) {
  auto g = io::read_gray_image(path);
  if (!g) return g.error();
  io::FloatImage out(g->width, g->height);
  for (std::size_t i = 0; i < g->pixels.size(); ++i)
    out.data[i] = static_cast<float>(g->pixels[i]) / static_cast<float>(scale);
  return out;
}

double bad1_over(ImageView<const float> d, const MiddleburyData& m,
                 const std::vector<std::uint8_t>& mask) {
  long bad = 0, n = 0;
  for (int y = 0; y < m.gt.height; ++y)
    for (int x = 0; x < m.gt.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * m.gt.width + x;
      if (!mask[i]) continue;
      const float v = d(x, y);
      ++n;
      bad += !std::isfinite(v) || std::fabs(v - m.gt.data[i]) > 1.0f;
    }
  return n ? 100.0 * static_cast<double>(bad) / static_cast<double>(n) : 0.0;
}

Bad1 bad1(ImageView<const float> d, const MiddleburyData& m) {
  return Bad1{bad1_over(d, m, m.nonocc), bad1_over(d, m, m.known)};
}

}  // namespace

std::span<const MiddleburyScene> middlebury_scenes() {
  return std::span<const MiddleburyScene>(kScenes).first(kMiddleburyCount);
}

std::span<const MiddleburyScene> real_rock_scenes() {
  return std::span<const MiddleburyScene>(kScenes).subspan(kMiddleburyCount);
}

const MiddleburyScene* find_middlebury_scene(const std::string& name) {
  for (const MiddleburyScene& s : kScenes)
    if (name == s.name) return &s;
  return nullptr;
}

std::vector<std::uint8_t> visible_in_right_view(const io::FloatImage& gt,
                                                const std::vector<std::uint8_t>& known) {
  std::vector<std::uint8_t> visible(known.size(), 0);
  for (int y = 0; y < gt.height; ++y) {
    float nearest_right_match = std::numeric_limits<float>::infinity();
    for (int x = gt.width - 1; x >= 0; --x) {
      const std::size_t i = static_cast<std::size_t>(y) * gt.width + x;
      if (!known[i]) continue;
      const float match = static_cast<float>(x) - gt.data[i];
      visible[i] = match < nearest_right_match;
      nearest_right_match = std::min(nearest_right_match, match);
    }
  }
  return visible;
}

std::string default_data_root(const char* source_dir) {
  return std::string(source_dir) + "/../shared/data";
}

Result<MiddleburyData> load_middlebury(const MiddleburyScene& s, const std::string& root) {
  const std::string dir = root + "/" + s.dir + "/";
  MiddleburyData m;
  m.scene = &s;
  auto l = io::read_gray_image(dir + s.left);
  if (!l) return l.error();
  auto r = io::read_gray_image(dir + s.right);
  if (!r) return r.error();
  auto gl = load_gt(dir + s.gt_left, s.gt_scale);
  if (!gl) return gl.error();
  m.left = std::move(*l);
  m.right = std::move(*r);
  m.gt = std::move(*gl);
  if (m.left.width != m.right.width || m.left.height != m.right.height ||
      m.gt.width != m.left.width || m.gt.height != m.left.height)
    return Error::make(Errc::invalid_argument, "middlebury %s: image and ground-truth sizes differ",
                       s.name);
  const int w = m.gt.width, h = m.gt.height;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  m.known.assign(n, 0);
  m.nonocc.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) m.known[i] = m.gt.data[i] > 0.0f;
  m.visible = visible_in_right_view(m.gt, m.known);
  if (s.gt_right == nullptr) {
    m.nonocc = m.known;
    return m;
  }
  auto gr = load_gt(dir + s.gt_right, s.gt_scale);
  if (!gr) return gr.error();
  if (gr->width != w || gr->height != h)
    return Error::make(Errc::invalid_argument, "middlebury %s: right ground truth size differs",
                       s.name);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      if (!m.known[i]) continue;
      const float d = m.gt.data[i];
      const int xr = x - static_cast<int>(std::lround(d));
      if (xr < 0 || xr >= w) continue;
      m.nonocc[i] = std::fabs(gr->data[static_cast<std::size_t>(y) * w + xr] - d) <= 1.0f;
    }
  return m;
}

Result<MiddleburyScore> score_middlebury(ImageView<const float> d, const MiddleburyData& m) {
  if (d.width() != m.gt.width || d.height() != m.gt.height)
    return Error::make(Errc::invalid_argument, "score: disparity is %dx%d, ground truth is %dx%d",
                       d.width(), d.height(), m.gt.width, m.gt.height);
  MiddleburyScore s;
  s.strict = bad1(d, m);
  long invalid = 0, known = 0;
  io::FloatImage filled(d.width(), d.height());
  for (int y = 0; y < d.height(); ++y)
    for (int x = 0; x < d.width(); ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * d.width() + x;
      filled.data[i] = d(x, y);
      if (m.known[i]) {
        ++known;
        invalid += !std::isfinite(d(x, y));
      }
    }
  fill_invalid_background(filled.view());
  s.filled = bad1(filled.view(), m);
  for (float& v : filled.data) v = std::round(v);  // inf stays inf
  s.filled_whole_visible = bad1_over(filled.view(), m, m.visible);
  s.invalid_pct = known ? 100.0 * static_cast<double>(invalid) / static_cast<double>(known) : 0.0;
  return s;
}

}  // namespace petra::eval
