#include "algo/camera/epipolar.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

namespace petra {

namespace {

struct RelativePose {
  Eigen::Matrix3d R;  // left camera -> right camera
  Eigen::Vector3d t;
};

RelativePose relative_pose(const StereoRig& rig) {
  const Eigen::Matrix3d r = rig.right.R * rig.left.R.transpose();
  return {r, rig.right.T_mm - r * rig.left.T_mm};
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// Bilinear gray value; the caller keeps (u, v) at least one pixel inside.
double sample(ConstGray8View img, double u, double v) {
  const int x0 = static_cast<int>(std::floor(u)), y0 = static_cast<int>(std::floor(v));
  const double a = u - x0, b = v - y0;
  const std::uint8_t* r0 = img.row(y0) + x0;
  const std::uint8_t* r1 = img.row(y0 + 1) + x0;
  const double top = (1 - a) * r0[0] + a * r0[1];
  const double bot = (1 - a) * r1[0] + a * r1[1];
  return (1 - b) * top + b * bot;
}

bool window_inside(ConstGray8View img, const Eigen::Vector2d& c, int h) {
  return c.x() - h >= 0 && c.y() - h >= 0 && c.x() + h + 1 <= img.width() - 1 &&
         c.y() + h + 1 <= img.height() - 1;
}

// Liang-Barsky: the part [t0, t1] of p0 + t (p1 - p0), t in [0, 1], inside the box.
bool clip_segment(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& lo,
                  const Eigen::Vector2d& hi, double& t0, double& t1) {
  t0 = 0;
  t1 = 1;
  const Eigen::Vector2d d = p1 - p0;
  const double p[4] = {-d.x(), d.x(), -d.y(), d.y()};
  const double q[4] = {p0.x() - lo.x(), hi.x() - p0.x(), p0.y() - lo.y(), hi.y() - p0.y()};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0) {
      if (q[k] < 0) return false;
      continue;
    }
    const double r = q[k] / p[k];
    if (p[k] < 0)
      t0 = std::max(t0, r);
    else
      t1 = std::min(t1, r);
  }
  return t0 <= t1;
}

}  // namespace

Eigen::Vector2d ideal_pixel(const TsaiCamera& cam, const Eigen::Vector2d& uv_px) {
  return sensor_to_pixel(cam, undistort_sensor(cam.kappa1, pixel_to_sensor(cam, uv_px)));
}

Result<Eigen::Vector2d> distorted_pixel(const TsaiCamera& cam, const Eigen::Vector2d& ideal_px) {
  auto pd = distort_sensor(cam.kappa1, pixel_to_sensor(cam, ideal_px));
  if (!pd) return pd.error();
  return sensor_to_pixel(cam, *pd);
}

Eigen::Matrix3d ideal_intrinsics(const TsaiCamera& cam) {
  Eigen::Matrix3d k;
  k << cam.f_mm * cam.sx / cam.dx_mm, 0, cam.cx_px, 0, cam.f_mm / cam.dy_mm, cam.cy_px, 0, 0, 1;
  return k;
}

Result<Eigen::Matrix3d> fundamental_matrix(const StereoRig& rig) {
  const RelativePose rel = relative_pose(rig);
  if (!(rel.t.norm() > 1e-9))
    return Error::make(Errc::degenerate,
                       "fundamental matrix: the cameras share their optical centre");
  const Eigen::Matrix3d f = ideal_intrinsics(rig.right).inverse().transpose() * skew(rel.t) *
                            rel.R * ideal_intrinsics(rig.left).inverse();
  return Eigen::Matrix3d(f / f.norm());
}

Eigen::Vector3d epipolar_line(const Eigen::Matrix3d& f, const Eigen::Vector2d& left_ideal_px) {
  const Eigen::Vector3d l = f * left_ideal_px.homogeneous();
  const double n = std::hypot(l.x(), l.y());
  return n > 0 ? Eigen::Vector3d(l / n) : l;
}

Result<Eigen::Vector2d> right_pixel_at_depth(const StereoRig& rig, const Eigen::Vector2d& left_px,
                                             double depth_mm) {
  if (!(depth_mm > 0))
    return Error::make(Errc::non_positive, "depth must be > 0 (got %g mm)", depth_mm);
  const Eigen::Vector2d n = pixel_to_normalised(rig.left, left_px);
  const Eigen::Vector3d pc(n.x() * depth_mm, n.y() * depth_mm, depth_mm);
  return project(rig.right, camera_to_world(rig.left, pc));
}

Result<RayMeeting> meet_rays(const Ray& a, const Ray& b) {
  const Eigen::Vector3d w0 = a.origin_mm - b.origin_mm;
  const double aa = a.direction.dot(a.direction), ab = a.direction.dot(b.direction);
  const double bb = b.direction.dot(b.direction);
  const double d = a.direction.dot(w0), e = b.direction.dot(w0);
  const double den = aa * bb - ab * ab;
  if (!(den > 1e-14 * aa * bb)) return Error::make(Errc::degenerate, "rays are parallel");
  const double s = (ab * e - bb * d) / den, t = (aa * e - ab * d) / den;
  const Eigen::Vector3d pa = a.origin_mm + s * a.direction, pb = b.origin_mm + t * b.direction;
  return RayMeeting{0.5 * (pa + pb), (pa - pb).norm()};
}

namespace {

Status check_click(const StereoRig& rig, ConstGray8View left, ConstGray8View right,
                   const Eigen::Vector2d& left_px, const ClickOptions& o) {
  const int h = o.half_window;
  if (h < 1 || h > kMaxClickHalfWindow)
    return Error::make(Errc::invalid_argument, "click: half window %d outside 1..%d", h,
                       kMaxClickHalfWindow);
  if (!(o.step_px > 0) || !(o.min_depth_mm > 0) || !(o.max_depth_mm > o.min_depth_mm))
    return Error::make(Errc::invalid_argument,
                       "click: need step > 0 and 0 < min depth < max depth");
  if (left.width() != rig.left.width || left.height() != rig.left.height)
    return Error::make(Errc::invalid_argument, "click: left image %dx%d, calibration %dx%d",
                       left.width(), left.height(), rig.left.width, rig.left.height);
  if (right.width() != rig.right.width || right.height() != rig.right.height)
    return Error::make(Errc::invalid_argument, "click: right image %dx%d, calibration %dx%d",
                       right.width(), right.height(), rig.right.width, rig.right.height);
  if (!left_px.allFinite() || !window_inside(left, left_px, h))
    return Error::make(Errc::out_of_range,
                       "click (%.1f, %.1f) is outside the left image or within %d px of its border",
                       left_px.x(), left_px.y(), h + 1);
  return ok_status();
}

// The click's window, zero mean, and its norm.
struct ClickTemplate {
  std::array<double, (2 * kMaxClickHalfWindow + 1) * (2 * kMaxClickHalfWindow + 1)> v{};
  int n = 0;  // pixels of the window
  double norm = 0;
};

Status click_template(ConstGray8View left, const Eigen::Vector2d& left_px, const ClickOptions& o,
                      ClickTemplate& t) {
  const int h = o.half_window;
  const int side = 2 * h + 1, n = side * side;
  t.n = n;
  double sum = 0, sum2 = 0;
  for (int j = -h, k = 0; j <= h; ++j)
    for (int i = -h; i <= h; ++i, ++k) {
      const double v = sample(left, left_px.x() + i, left_px.y() + j);
      t.v[static_cast<std::size_t>(k)] = v;
      sum += v;
      sum2 += v * v;
    }
  const double mean = sum / n;
  const double var = std::max(0.0, sum2 / n - mean * mean);
  if (std::sqrt(var) < o.min_texture)
    return Error::make(Errc::degenerate,
                       "click: window has no texture (std dev %.1f < %.1f gray levels)",
                       std::sqrt(var), o.min_texture);
  double tnorm = 0;
  for (int k = 0; k < n; ++k) {
    t.v[static_cast<std::size_t>(k)] -= mean;
    tnorm += t.v[static_cast<std::size_t>(k)] * t.v[static_cast<std::size_t>(k)];
  }
  t.norm = std::sqrt(tnorm);
  return ok_status();
}

// The searched part of the epipolar curve, in ideal right pixels: count
// samples `step` apart from p0 + t0 (p1 - p0).
struct EpipolarSegment {
  Eigen::Vector2d p0, p1;
  double t0 = 0;
  double full = 0;  // |p1 - p0|
  double step = 0;
  int count = 0;

  Eigen::Vector2d ideal_at(double k) const {
    const double t = full > 0 ? t0 + k * step / full : t0;
    return p0 + t * (p1 - p0);
  }
};

// The box of the right camera's ideal image (its border, undistorted).
void ideal_image_box(const StereoRig& rig, ConstGray8View right, Eigen::Vector2d& lo,
                     Eigen::Vector2d& hi) {
  lo = Eigen::Vector2d(1e300, 1e300);
  hi = Eigen::Vector2d(-1e300, -1e300);
  for (int k = 0; k <= 8; ++k) {
    const double fu = k / 8.0 * (right.width() - 1), fv = k / 8.0 * (right.height() - 1);
    for (const Eigen::Vector2d& b :
         {Eigen::Vector2d(fu, 0), Eigen::Vector2d(fu, right.height() - 1.0), Eigen::Vector2d(0, fv),
          Eigen::Vector2d(right.width() - 1.0, fv)}) {
      const Eigen::Vector2d q = ideal_pixel(rig.right, b);
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
  }
}

Result<EpipolarSegment> epipolar_segment(const StereoRig& rig, ConstGray8View right,
                                         const Eigen::Vector2d& left_px, const ClickOptions& o) {
  // The ray at inverse depth rho appears at K_r (R d + rho t): a straight
  // segment in ideal pixels while it stays in front of the right camera.
  const RelativePose rel = relative_pose(rig);
  const Eigen::Vector2d nl = pixel_to_normalised(rig.left, left_px);
  const Eigen::Vector3d rd = rel.R * Eigen::Vector3d(nl.x(), nl.y(), 1.0);
  const Eigen::Matrix3d kr = ideal_intrinsics(rig.right);
  double rho0 = 1.0 / o.max_depth_mm, rho1 = 1.0 / o.min_depth_mm;
  auto z_at = [&](double rho) { return rd.z() + rho * rel.t.z(); };
  if (!(z_at(rho0) > 1e-9))
    return Error::make(Errc::no_solution,
                       "click: the ray is behind the right camera at the far end");
  if (!(z_at(rho1) > 1e-9))
    rho1 = (1e-9 - rd.z()) / rel.t.z() * 0.999;  // stop before the camera plane
  EpipolarSegment seg;
  seg.p0 = (kr * (rd + rho0 * rel.t)).hnormalized();
  seg.p1 = (kr * (rd + rho1 * rel.t)).hnormalized();

  // Clip to the ideal image of the right camera.
  Eigen::Vector2d lo, hi;
  ideal_image_box(rig, right, lo, hi);
  double t0 = 0, t1 = 0;
  if (!clip_segment(seg.p0, seg.p1, lo, hi, t0, t1))
    return Error::make(Errc::no_solution, "click: the epipolar segment misses the right image");
  seg.t0 = t0;
  seg.full = (seg.p1 - seg.p0).norm();
  const double length = seg.full * (t1 - t0);
  double step = o.step_px;
  if (length / step + 1 > kMaxClickSamples) step = length / (kMaxClickSamples - 1);
  seg.step = step;
  seg.count = std::max(1, static_cast<int>(length / step) + 1);
  return seg;
}

// ZNCC of the template at each sample (-2 where the window does not fit);
// returns the best sample, -1 when none fits.
int score_segment(const StereoRig& rig, ConstGray8View right, int h, const ClickTemplate& t,
                  const EpipolarSegment& seg, std::array<double, kMaxClickSamples>& score) {
  int best = -1;
  for (int k = 0; k < seg.count; ++k) {
    score[static_cast<std::size_t>(k)] = -2.0;  // not scored
    auto c = distorted_pixel(rig.right, seg.ideal_at(k));
    if (!c || !window_inside(right, *c, h)) continue;
    double s = 0, s2 = 0, cross = 0;
    for (int j = -h, m = 0; j <= h; ++j)
      for (int i = -h; i <= h; ++i, ++m) {
        const double v = sample(right, c->x() + i, c->y() + j);
        s += v;
        s2 += v * v;
        cross += v * t.v[static_cast<std::size_t>(m)];
      }
    const double rvar = s2 - s * s / t.n;
    // Sum of zero-mean template times (v - mean_v) equals sum of template times v.
    const double zncc = rvar > 0 ? cross / (t.norm * std::sqrt(rvar)) : 0.0;
    score[static_cast<std::size_t>(k)] = zncc;
    if (best < 0 || zncc > score[static_cast<std::size_t>(best)]) best = k;
  }
  return best;
}

// The best sample's parabola offset (its neighbours both scored), in samples.
double peak_offset(const std::array<double, kMaxClickSamples>& score, int best, int count) {
  double offset = 0;
  if (best > 0 && best + 1 < count && score[static_cast<std::size_t>(best) - 1] > -2 &&
      score[static_cast<std::size_t>(best) + 1] > -2) {
    const double a = score[static_cast<std::size_t>(best) - 1],
                 b = score[static_cast<std::size_t>(best)],
                 c = score[static_cast<std::size_t>(best) + 1];
    const double den = a - 2 * b + c;
    if (den < 0) offset = std::clamp(0.5 * (a - c) / den, -0.5, 0.5);
  }
  return offset;
}

}  // namespace

Result<ClickMatch> transfer_click(const StereoRig& rig, ConstGray8View left, ConstGray8View right,
                                  const Eigen::Vector2d& left_px, const ClickOptions& o) {
  PETRA_TRY(check_click(rig, left, right, left_px, o));
  const int h = o.half_window;
  ClickTemplate tmpl;
  PETRA_TRY(click_template(left, left_px, o, tmpl));
  auto segment = epipolar_segment(rig, right, left_px, o);
  if (!segment) return segment.error();
  const EpipolarSegment& seg = *segment;
  const int count = seg.count;

  std::array<double, kMaxClickSamples> score{};
  const int best = score_segment(rig, right, h, tmpl, seg, score);
  if (best < 0)
    return Error::make(
        Errc::no_solution,
        "click: no position of the epipolar curve fits the window in the right image");

  ClickMatch m;
  m.samples = count;
  int first = 0, last = count - 1;
  while (score[static_cast<std::size_t>(first)] < -1.5) ++first;
  while (score[static_cast<std::size_t>(last)] < -1.5) --last;
  m.at_search_end = best == first || best == last;
  m.score = score[static_cast<std::size_t>(best)];
  const double offset = peak_offset(score, best, count);
  auto matched = distorted_pixel(rig.right, seg.ideal_at(best + offset));
  if (!matched) return matched.error();
  m.right_px = *matched;
  const double apart = (2 * h + 1) / seg.step;  // samples in one window width
  for (int k = 0; k < count; ++k)
    if (std::abs(k - best) > apart)
      m.runner_up = std::max(m.runner_up, score[static_cast<std::size_t>(k)]);
  auto meet = meet_rays(pixel_to_ray(rig.left, left_px), pixel_to_ray(rig.right, m.right_px));
  if (!meet) return meet.error();
  m.point_mm = meet->point_mm;
  m.ray_gap_mm = meet->gap_mm;
  m.depth_mm = world_to_camera(rig.left, m.point_mm).z();
  return m;
}

}  // namespace petra
