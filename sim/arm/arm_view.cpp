#include "sim/arm/arm_view.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <functional>
#include <numbers>

namespace petra::sim {

namespace {

const Rgb kInk{30, 30, 40};
const Rgb kArm{35, 80, 160};
const Rgb kGhost{150, 160, 180};
const Rgb kTool{220, 110, 20};
const Rgb kPlane{240, 150, 40};
const Rgb kOtherPlane{120, 140, 170};
const Rgb kNormal{200, 30, 40};
const Rgb kApproach{20, 150, 60};
const Rgb kGround{200, 195, 185};
const Rgb kRefused{200, 20, 20};
const Rgb kPanel{252, 252, 250};

using Project = std::function<Eigen::Vector2d(const Eigen::Vector3d&)>;

[[gnu::format(printf, 1, 2)]] std::string fmt(const char* f, ...) {
  char buf[200];
  va_list args;
  va_start(args, f);
  std::vsnprintf(buf, sizeof buf, f, args);
  va_end(args);
  return buf;
}

std::string joints_text(const char* label, const arm::JointVector& q) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s th1..th5 = %.2f, %.2f, %.2f, %.2f, %.2f deg", label,
                q[0] / arm::kRadPerDeg, q[1] / arm::kRadPerDeg, q[2] / arm::kRadPerDeg,
                q[3] / arm::kRadPerDeg, q[4] / arm::kRadPerDeg);
  return buf;
}

// Two unit vectors spanning the plane perpendicular to n.
void plane_basis(const Eigen::Vector3d& n, Eigen::Vector3d& a, Eigen::Vector3d& b) {
  const Eigen::Vector3d helper =
      std::abs(n.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  a = n.cross(helper).normalized();
  b = n.cross(a).normalized();
}

std::array<Eigen::Vector3d, 4> patch(const OutputPlane& p) {
  const double half = 0.5 * std::clamp(p.area_mm2 > 0 ? std::sqrt(p.area_mm2) : 50.0, 25.0, 120.0);
  Eigen::Vector3d a, b;
  plane_basis(p.normal, a, b);
  const Eigen::Vector3d c = p.centroid_mm;
  return {c + half * (a + b), c + half * (a - b), c - half * (a + b), c - half * (a - b)};
}

// Everything drawn, in world coordinates, shared by the three panels.
struct Scene3d {
  std::vector<std::array<Eigen::Vector3d, 4>> other_planes;
  std::array<Eigen::Vector3d, 4> chosen_patch{};
  Eigen::Vector3d centroid, normal_tip, standoff_tip;
  arm::ArmSkeleton final_pose, ghost_pose;
  bool planned = false;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> ground_lines;
  Eigen::Vector3d base, up;
  std::optional<Eigen::Vector3d> base_foot, target_foot;  // on the ground, below them
};

Scene3d build_scene(const ArmViewInput& in, const ArmView& view) {
  Scene3d s;
  const OutputPlane& p = in.planes[in.chosen];
  for (std::size_t i = 0; i < in.planes.size(); ++i) {
    if (i != in.chosen) s.other_planes.push_back(patch(in.planes[i]));
  }
  s.chosen_patch = patch(p);
  s.centroid = p.centroid_mm;
  s.normal_tip = p.centroid_mm + (in.standoff_mm + 60.0) * p.normal;
  s.standoff_tip = p.centroid_mm + in.standoff_mm * p.normal;
  s.planned = view.plan.ok();
  s.final_pose =
      arm::arm_skeleton(in.geometry, s.planned ? view.plan.approach.contact_q : in.start);
  s.ghost_pose =
      arm::arm_skeleton(in.geometry, s.planned ? view.plan.approach.standoff_q : in.start);
  s.base = in.geometry.world_from_base.translation();
  s.up = in.geometry.world_from_base.linear().col(2);
  if (in.ground) {
    const Eigen::Vector3d n = in.ground->normal;
    const double d = in.ground->d_mm;
    Eigen::Vector3d a, b;
    plane_basis(n, a, b);
    // A 100 mm grid under the base and the target.
    s.base_foot = s.base - (n.dot(s.base) + d) * n;
    s.target_foot = s.centroid - (n.dot(s.centroid) + d) * n;
    const Eigen::Vector3d mid = 0.5 * (s.base + s.centroid);
    const Eigen::Vector3d origin = mid - (n.dot(mid) + d) * n;
    const double half = 0.5 * (s.centroid - s.base).norm() + 300.0;
    const int lines = static_cast<int>(half / 100.0);
    for (int k = -lines; k <= lines; ++k) {
      s.ground_lines.emplace_back(origin + k * 100.0 * a - half * b,
                                  origin + k * 100.0 * a + half * b);
      s.ground_lines.emplace_back(origin + k * 100.0 * b - half * a,
                                  origin + k * 100.0 * b + half * a);
    }
  }
  return s;
}

// Fits the points a projection gives into a panel, keeping the aspect ratio.
Project fit(const Project& raw, const std::vector<Eigen::Vector3d>& points, double x, double y,
            double w, double h) {
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const auto& p : points) {
    const Eigen::Vector2d q = raw(p);
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  const Eigen::Vector2d size = (hi - lo).cwiseMax(Eigen::Vector2d(1e-6, 1e-6));
  const double scale = 0.86 * std::min(w / size.x(), h / size.y());
  const Eigen::Vector2d centre = 0.5 * (lo + hi);
  const Eigen::Vector2d panel_centre(x + 0.5 * w, y + 0.5 * h);
  return [raw, scale, centre, panel_centre](const Eigen::Vector3d& p) {
    return Eigen::Vector2d(panel_centre + scale * (raw(p) - centre));
  };
}

std::vector<Eigen::Vector3d> key_points(const Scene3d& s) {
  std::vector<Eigen::Vector3d> pts;
  for (const auto& p : s.final_pose.points_mm) pts.push_back(p);
  for (const auto& p : s.ghost_pose.points_mm) pts.push_back(p);
  for (const auto& p : s.chosen_patch) pts.push_back(p);
  pts.push_back(s.normal_tip);
  if (s.base_foot) pts.push_back(*s.base_foot);
  if (s.target_foot) pts.push_back(*s.target_foot);
  return pts;
}

void draw_skeleton(Canvas& c, const Project& P, const arm::ArmSkeleton& sk, bool ghost) {
  const auto& pt = sk.points_mm;
  const Rgb link = ghost ? kGhost : kArm;
  const double op = ghost ? 0.7 : 1.0;
  c.line(P(pt[0]), P(pt[1]), link, ghost ? 5 : 9, op);  // pedestal to shoulder
  for (int i = 1; i < 4; ++i) c.line(P(pt[i]), P(pt[i + 1]), link, ghost ? 4 : 7, op);
  c.line(P(pt[4]), P(pt[5]), ghost ? kGhost : kTool, ghost ? 4 : 7, op);  // grinder
  for (int i = 0; i < 5; ++i) c.disc(P(pt[i]), ghost ? 4 : 6, ghost ? kGhost : kInk, op);
  c.disc(P(pt[5]), ghost ? 3 : 5, ghost ? kGhost : kTool, op);
}

void draw_panel(Canvas& c, const Scene3d& s, const Project& P, const char* title, double x,
                double y, double w, double h) {
  c.rect(x, y, w, h, kPanel);
  c.begin_clip(x, y, w, h);
  for (const auto& [a, b] : s.ground_lines) c.line(P(a), P(b), kGround, 1);
  for (const auto& q : s.other_planes) {
    const Eigen::Vector2d pts[4] = {P(q[0]), P(q[1]), P(q[2]), P(q[3])};
    c.polygon(pts, kOtherPlane, 0.35);
  }
  if (s.base_foot) c.line(P(s.base), P(*s.base_foot), kGhost, 12);  // the rover's mount post
  if (s.target_foot) c.line(P(s.centroid), P(*s.target_foot), kGround, 1);
  const Eigen::Vector2d chosen[4] = {P(s.chosen_patch[0]), P(s.chosen_patch[1]),
                                     P(s.chosen_patch[2]), P(s.chosen_patch[3])};
  c.polygon(chosen, kPlane, 0.55);
  draw_skeleton(c, P, s.ghost_pose, true);
  // Approach: dashed from the standoff point to the centroid.
  const int dashes = 8;
  for (int k = 0; k < dashes; k += 2) {
    const Eigen::Vector3d a = s.standoff_tip + (s.centroid - s.standoff_tip) * (double(k) / dashes);
    const Eigen::Vector3d b =
        s.standoff_tip + (s.centroid - s.standoff_tip) * (double(k + 1) / dashes);
    c.line(P(a), P(b), kApproach, 3);
  }
  draw_skeleton(c, P, s.final_pose, false);
  for (int k = 0; k < dashes; k += 2) {
    const Eigen::Vector3d a = s.standoff_tip + (s.centroid - s.standoff_tip) * (double(k) / dashes);
    const Eigen::Vector3d b =
        s.standoff_tip + (s.centroid - s.standoff_tip) * (double(k + 1) / dashes);
    c.line(P(a), P(b), kApproach, 3);
  }
  // The normal, thin, over the tool (the tool lies along it) and past the standoff.
  c.line(P(s.centroid), P(s.normal_tip), kNormal, 2);
  c.disc(P(s.normal_tip), 4, kNormal);
  c.disc(P(s.standoff_tip), 4, kApproach);
  c.disc(P(s.centroid), 4, kNormal);
  c.end_clip();
  c.line({x, y}, {x + w, y}, kGhost, 1);
  c.line({x, y + h}, {x + w, y + h}, kGhost, 1);
  c.line({x, y}, {x, y + h}, kGhost, 1);
  c.line({x + w, y}, {x + w, y + h}, kGhost, 1);
  c.text({x + 10, y + 10}, title, kInk, 2);
}

}  // namespace

Result<ArmView> plan_arm_view(const ArmViewInput& in) {
  if (in.planes.empty()) return Error::make(Errc::invalid_argument, "arm-view: no planes");
  if (in.chosen >= in.planes.size()) {
    return Error::make(Errc::out_of_range, "arm-view: plane %zu of %zu", in.chosen + 1,
                       in.planes.size());
  }
  PETRA_TRY(arm::validate_geometry(in.geometry));
  PETRA_TRY(arm::validate_limits(in.limits));
  const OutputPlane& p = in.planes[in.chosen];
  ArmView v;
  arm::ApproachRequest req;
  req.centroid_mm = p.centroid_mm;
  req.normal = p.normal;
  req.standoff_mm = in.standoff_mm;
  v.plan = arm::plan_approach(in.geometry, in.limits, req, in.start);
  v.summary.push_back(
      fmt("plane %zu: centroid (%.1f, %.1f, %.1f) mm, normal (%.3f, %.3f, %.3f), standoff %.0f mm",
          in.chosen + 1, p.centroid_mm.x(), p.centroid_mm.y(), p.centroid_mm.z(), p.normal.x(),
          p.normal.y(), p.normal.z(), in.standoff_mm));
  if (v.plan.ok()) {
    const arm::StraightApproach& a = v.plan.approach;
    v.summary.push_back(joints_text("contact: ", a.contact_q));
    v.summary.push_back(joints_text("standoff:", a.standoff_q));
    v.summary.push_back(fmt("approach: %.0f mm along -normal at %.1f mm/s, %.1f s", a.length_mm,
                            a.tool_speed_mm_s, a.duration_s()));
  } else {
    v.summary.push_back(std::string("REFUSED: ") + v.plan.error(in.limits).message);
    v.summary.push_back(joints_text("arm shown at its start pose:", in.start));
  }
  return v;
}

void draw_arm_view(const ArmViewInput& in, const ArmView& view, Canvas& c) {
  const Scene3d s = build_scene(in, view);
  const double W = c.width();
  const double H = c.height();
  const double text_h = 40.0 + 26.0 * static_cast<double>(view.summary.size());
  const double big_w = 0.58 * W;
  const double panel_h = H - text_h - 20.0;
  const std::vector<Eigen::Vector3d> pts = key_points(s);

  // 3-D view: from beside the arm and a little behind, 30 deg above.
  const Eigen::Vector3d up = s.up;
  Eigen::Vector3d reach = s.centroid - s.base;
  reach -= reach.dot(up) * up;
  if (reach.norm() < 1.0) reach = in.geometry.world_from_base.linear().col(0);
  reach.normalize();
  const Eigen::Vector3d side = up.cross(reach).normalized();  // left of the arm
  const Eigen::Vector3d look_from =
      (-side * std::cos(40 * arm::kRadPerDeg) - reach * std::sin(40 * arm::kRadPerDeg))
          .normalized();
  const Eigen::Vector3d centre = 0.5 * (s.base + s.centroid);
  const double dist = 3.0 * std::max(400.0, (s.centroid - s.base).norm());
  const Eigen::Vector3d eye = centre + dist * (std::cos(30 * arm::kRadPerDeg) * look_from +
                                               std::sin(30 * arm::kRadPerDeg) * up);
  const Eigen::Vector3d fwd = (centre - eye).normalized();
  const Eigen::Vector3d right = fwd.cross(up).normalized();
  const Eigen::Vector3d cam_up = right.cross(fwd);
  const Project perspective = [=](const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - eye;
    const double depth = std::max(1.0, d.dot(fwd));
    return Eigen::Vector2d(d.dot(right) / depth, -d.dot(cam_up) / depth);
  };
  draw_panel(c, s, fit(perspective, pts, 10, 10, big_w - 15, panel_h), "3-D VIEW", 10, 10,
             big_w - 15, panel_h);

  // Side view: the vertical plane of th1 at the final pose.
  const double th1 = s.planned ? view.plan.approach.contact_q[0] : in.start[0];
  const Eigen::Matrix3d rb = in.geometry.world_from_base.linear();
  const Eigen::Vector3d e = rb * Eigen::Vector3d(std::cos(th1), std::sin(th1), 0.0);
  const Eigen::Vector3d base = s.base;
  const Project side_view = [=](const Eigen::Vector3d& p) {
    return Eigen::Vector2d((p - base).dot(e), -(p - base).dot(up));
  };
  char title[96];
  std::snprintf(title, sizeof title, "SIDE VIEW, ARM PLANE TH1 = %.1f DEG", th1 / arm::kRadPerDeg);
  const double rx = big_w + 5;
  const double rw = W - big_w - 15;
  const double half_h = 0.5 * (panel_h - 10);
  draw_panel(c, s, fit(side_view, pts, rx, 10, rw, half_h), title, rx, 10, rw, half_h);

  // Top view: forward (base x) up the page.
  const Eigen::Vector3d bx = rb.col(0);
  const Eigen::Vector3d by = rb.col(1);
  const Project top = [=](const Eigen::Vector3d& p) {
    return Eigen::Vector2d(-(p - base).dot(by), -(p - base).dot(bx));
  };
  draw_panel(c, s, fit(top, pts, rx, 20 + half_h, rw, half_h), "TOP VIEW, ARM FORWARD UP", rx,
             20 + half_h, rw, half_h);

  // The numbers.
  double y = H - text_h + 10;
  for (std::size_t i = 0; i < view.summary.size(); ++i) {
    const bool refused = view.summary[i].rfind("REFUSED", 0) == 0;
    c.text({20, y}, view.summary[i], refused ? kRefused : kInk, 2);
    y += 26;
  }
  c.text({20, y + 4},
         s.planned ? "BLUE ARM: CONTACT POSE   GRAY: STANDOFF POSE   GREEN: STANDOFF POINT AND "
                     "APPROACH   RED: NORMAL"
                   : "BLUE ARM: START POSE (NO PLAN)   ORANGE: TARGET PLANE   RED: NORMAL",
         kGhost, 2);
}

}  // namespace petra::sim
