#include "algo/arm/kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace petra::arm {

namespace {

constexpr double kPi = std::numbers::pi;

// Maps an angle to (centre - pi, centre + pi], so a joint value is read next to
// the middle of its range (th4's 35..180 deg needs more than (-pi, pi]).
double wrap_near(double angle, double centre) {
  double d = std::remainder(angle - centre, 2.0 * kPi);  // in [-pi, pi]
  if (d <= -kPi) d += 2.0 * kPi;
  return centre + d;
}

// Everything the closed-form FK computes, in the base frame.
struct PlanarPose {
  Eigen::Vector3d e;  // horizontal direction of the arm plane
  Eigen::Vector3d n;  // plane normal (left of the arm): z x e
  double alpha3 = 0;  // hand angle above the horizontal
  Eigen::Vector3d shoulder, elbow, wrist, hand_end, tip, axis;
};

PlanarPose planar_pose(const ArmGeometry& g, const JointVector& q) {
  PlanarPose p;
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  p.e = Eigen::Vector3d(std::cos(q[0]), std::sin(q[0]), 0.0);
  p.n = Eigen::Vector3d(-std::sin(q[0]), std::cos(q[0]), 0.0);
  const double a1 = q[1];
  const double a2 = a1 - q[2];
  const double a3 = a2 + kPi - q[3];
  p.alpha3 = a3;
  auto in_plane = [&](double r, double h) -> Eigen::Vector3d { return r * p.e + h * z; };
  p.shoulder = in_plane(g.shoulder_offset_mm, g.shoulder_height_mm);
  p.elbow = p.shoulder + g.upper_arm_mm * in_plane(std::cos(a1), std::sin(a1));
  p.wrist = p.elbow + g.forearm_mm * in_plane(std::cos(a2), std::sin(a2));
  p.hand_end = p.wrist + g.hand_mm * in_plane(std::cos(a3), std::sin(a3));
  const Eigen::Vector3d across = in_plane(std::sin(a3), -std::cos(a3));  // tool at th5 = 0
  p.axis = std::cos(q[4]) * across + std::sin(q[4]) * p.n;
  p.tip = p.hand_end + g.tool_mm * p.axis;
  return p;
}

bool finite(const Eigen::Vector3d& v) {
  return v.allFinite();
}

// One closed-form branch: given th1 and the elbow sign, the rest follows.
IkSolution solve_branch(const ArmGeometry& g, const JointLimits& limits,
                        const Eigen::Vector3d& hand_end, const Eigen::Vector3d& axis, double th1,
                        double elbow_sign) {
  IkSolution s;
  const Eigen::Vector3d e(std::cos(th1), std::sin(th1), 0.0);
  const Eigen::Vector3d n(-std::sin(th1), std::cos(th1), 0.0);
  // Tool axis = cos(th5) * across + sin(th5) * n, with `across` in the plane.
  const double sin5 = std::clamp(axis.dot(n), -1.0, 1.0);
  const double th5 = std::asin(sin5);
  const double cos5 = std::cos(th5);
  // across = (sin a3, -cos a3) in (e, z); cos5 >= cos 90deg only at a degenerate axis.
  const double across_e = axis.dot(e);
  const double across_z = axis.z();
  double alpha3 = 0.0;
  if (cos5 > 1e-12) alpha3 = std::atan2(across_e / cos5, -across_z / cos5);
  // Wrist centre in plane coordinates (r along e, h along z), relative to the shoulder.
  const double r = hand_end.dot(e) - g.hand_mm * std::cos(alpha3) - g.shoulder_offset_mm;
  const double h = hand_end.z() - g.hand_mm * std::sin(alpha3) - g.shoulder_height_mm;
  const double dist = std::hypot(r, h);
  const double l2 = g.upper_arm_mm;
  const double l3 = g.forearm_mm;
  const double reach_tol = 1e-9 * (l2 + l3);
  if (dist > l2 + l3 + reach_tol) {
    s.reason = ArmReason::beyond_reach;
    s.value = dist - (l2 + l3);
    return s;
  }
  if (dist < std::abs(l2 - l3) - reach_tol) {
    s.reason = ArmReason::inside_reach;
    s.value = std::abs(l2 - l3) - dist;
    return s;
  }
  // |W - S|^2 = l2^2 + l3^2 + 2 l2 l3 cos(th3).
  const double c3 = std::clamp((dist * dist - l2 * l2 - l3 * l3) / (2.0 * l2 * l3), -1.0, 1.0);
  const double th3 = elbow_sign * std::acos(c3);
  const double th2 = std::atan2(h, r) + std::atan2(l3 * std::sin(th3), l2 + l3 * std::cos(th3));
  const double th4 = th2 - th3 + kPi - alpha3;

  s.q[0] = th1;
  s.q[1] = th2;
  s.q[2] = th3;
  s.q[3] = th4;
  s.q[4] = th5;
  for (int j = 0; j < kJointCount; ++j) {
    s.q[j] = wrap_near(s.q[j], 0.5 * (limits.min_rad[j] + limits.max_rad[j]));
  }
  const int bad = first_joint_outside(limits, s.q);
  if (bad >= 0) {
    s.reason = ArmReason::joint_limit;
    s.joint = bad + 1;
    s.value = s.q[bad];
    return s;
  }
  // Inside the range (within tolerance): pin exactly onto it.
  for (int j = 0; j < kJointCount; ++j) {
    s.q[j] = std::clamp(s.q[j], limits.min_rad[j], limits.max_rad[j]);
  }
  return s;
}

// Total excursion outside the ranges: ranks failed branches.
double limit_excess(const JointLimits& limits, const JointVector& q) {
  double excess = 0.0;
  for (int j = 0; j < kJointCount; ++j) {
    excess += std::max(0.0, limits.min_rad[j] - q[j]) + std::max(0.0, q[j] - limits.max_rad[j]);
  }
  return excess;
}

double joint_distance(const JointVector& a, const JointVector& b) {
  double d = 0.0;
  for (int j = 0; j < kJointCount; ++j) d += std::abs(std::remainder(a[j] - b[j], 2.0 * kPi));
  return d;
}

}  // namespace

Eigen::Isometry3d default_rover_mount() {
  Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
  m.linear() = Eigen::Matrix3d(Eigen::AngleAxisd(0.5 * kPi, Eigen::Vector3d::UnitZ()));
  m.translation() = Eigen::Vector3d(300.0, 100.0, 100.0);
  return m;
}

ArmGeometry rover_arm_geometry() {
  ArmGeometry g;
  g.world_from_base = default_rover_mount();
  return g;
}

JointLimits default_joint_limits() {
  JointLimits l;
  const double lo[kJointCount] = {0.0, 0.0, 0.0, 35.0, -45.0};
  const double hi[kJointCount] = {90.0, 90.0, 145.0, 180.0, 45.0};
  for (int j = 0; j < kJointCount; ++j) {
    l.min_rad[j] = lo[j] * kRadPerDeg;
    l.max_rad[j] = hi[j] * kRadPerDeg;
    l.max_velocity_rad_s[j] = 30.0 * kRadPerDeg;
    l.max_acceleration_rad_s2[j] = 60.0 * kRadPerDeg;
  }
  return l;
}

JointVector stow_pose() {
  JointVector q;
  q << 0.0, 0.0, 145.0 * kRadPerDeg, 35.0 * kRadPerDeg, 0.0;
  return q;
}

Status validate_geometry(const ArmGeometry& g) {
  const struct {
    const char* name;
    double value;
  } lengths[] = {{"shoulder_height_mm", g.shoulder_height_mm},
                 {"shoulder_offset_mm", g.shoulder_offset_mm},
                 {"upper_arm_mm", g.upper_arm_mm},
                 {"forearm_mm", g.forearm_mm},
                 {"hand_mm", g.hand_mm},
                 {"tool_mm", g.tool_mm}};
  for (const auto& l : lengths) {
    if (!std::isfinite(l.value))
      return Error::make(Errc::invalid_argument, "arm.%s is not finite", l.name);
  }
  // The offsets may be zero or negative (a shoulder set back); links must have length.
  for (std::size_t i = 2; i < 6; ++i) {
    if (!(lengths[i].value > 0.0)) {
      return Error::make(Errc::non_positive, "arm.%s must be > 0 (got %g)", lengths[i].name,
                         lengths[i].value);
    }
  }
  const Eigen::Matrix3d r = g.world_from_base.linear();
  if (!r.allFinite() || !g.world_from_base.translation().allFinite()) {
    return Error::make(Errc::invalid_argument, "arm.world_from_base is not finite");
  }
  const double ortho = (r * r.transpose() - Eigen::Matrix3d::Identity()).norm();
  if (ortho > 1e-6 || r.determinant() < 0.0) {
    return Error::make(
        Errc::not_orthonormal,
        "arm.world_from_base rotation is not a rotation (|R R^T - I| = %.3g, det %.3g)", ortho,
        r.determinant());
  }
  return ok_status();
}

Status validate_limits(const JointLimits& l) {
  for (int j = 0; j < kJointCount; ++j) {
    if (!std::isfinite(l.min_rad[j]) || !std::isfinite(l.max_rad[j]) ||
        !(l.min_rad[j] <= l.max_rad[j])) {
      return Error::make(Errc::invalid_argument,
                         "limits.th%d range [%g, %g] rad is empty or not finite", j + 1,
                         l.min_rad[j], l.max_rad[j]);
    }
    if (l.max_rad[j] - l.min_rad[j] >= 2.0 * kPi) {
      return Error::make(Errc::out_of_range, "limits.th%d range spans a full turn or more", j + 1);
    }
    if (!(l.max_velocity_rad_s[j] > 0.0) || !std::isfinite(l.max_velocity_rad_s[j])) {
      return Error::make(Errc::non_positive, "limits.th%d max velocity must be > 0 (got %g rad/s)",
                         j + 1, l.max_velocity_rad_s[j]);
    }
    if (!(l.max_acceleration_rad_s2[j] > 0.0) || !std::isfinite(l.max_acceleration_rad_s2[j])) {
      return Error::make(Errc::non_positive,
                         "limits.th%d max acceleration must be > 0 (got %g rad/s^2)", j + 1,
                         l.max_acceleration_rad_s2[j]);
    }
  }
  return ok_status();
}

Eigen::Isometry3d tool_frame(const ArmGeometry& g, const JointVector& q) {
  const PlanarPose p = planar_pose(g, q);
  // Hand frame: x along the hand, y the plane normal; the tool frame is the hand
  // frame rolled by th5 + pi about x, so that z is the tool axis.
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d hand_x = std::cos(p.alpha3) * p.e + std::sin(p.alpha3) * z;
  const Eigen::Vector3d hand_z = -std::sin(p.alpha3) * p.e + std::cos(p.alpha3) * z;
  Eigen::Matrix3d r;
  r.col(0) = hand_x;
  r.col(1) = -std::cos(q[4]) * p.n - std::sin(q[4]) * hand_z;
  r.col(2) = p.axis;
  Eigen::Isometry3d base_from_tool = Eigen::Isometry3d::Identity();
  base_from_tool.linear() = r;
  base_from_tool.translation() = p.tip;
  return g.world_from_base * base_from_tool;
}

ToolPose forward_kinematics(const ArmGeometry& g, const JointVector& q) {
  const PlanarPose p = planar_pose(g, q);
  ToolPose t;
  t.tip_mm = g.world_from_base * p.tip;
  t.axis = g.world_from_base.linear() * p.axis;
  return t;
}

ArmSkeleton arm_skeleton(const ArmGeometry& g, const JointVector& q) {
  const PlanarPose p = planar_pose(g, q);
  ArmSkeleton s;
  const Eigen::Vector3d base_points[6] = {
      Eigen::Vector3d::Zero(), p.shoulder, p.elbow, p.wrist, p.hand_end, p.tip};
  for (std::size_t i = 0; i < 6; ++i) s.points_mm[i] = g.world_from_base * base_points[i];
  return s;
}

const char* arm_reason_name(ArmReason reason) {
  switch (reason) {
    case ArmReason::ok:
      return "ok";
    case ArmReason::bad_target:
      return "bad_target";
    case ArmReason::beyond_reach:
      return "beyond_reach";
    case ArmReason::inside_reach:
      return "inside_reach";
    case ArmReason::joint_limit:
      return "joint_limit";
    case ArmReason::path_blocked:
      return "path_blocked";
    case ArmReason::bad_request:
      return "bad_request";
  }
  return "unknown";
}

Error IkSolution::error(const JointLimits& limits) const {
  switch (reason) {
    case ArmReason::ok:
      return Error{};
    case ArmReason::bad_target:
      return Error::make(Errc::invalid_argument,
                         "arm target: point not finite or axis not a unit vector");
    case ArmReason::beyond_reach:
      return Error::make(Errc::no_solution,
                         "arm target beyond reach: wrist %.1f mm too far from the shoulder", value);
    case ArmReason::inside_reach:
      return Error::make(Errc::no_solution,
                         "arm target too close: wrist %.1f mm inside the minimum reach", value);
    case ArmReason::joint_limit: {
      const int j = std::clamp(joint, 1, kJointCount) - 1;
      return Error::make(Errc::out_of_range, "th%d = %.2f deg outside %.0f..%.0f deg", joint,
                         value / kRadPerDeg, limits.min_rad[j] / kRadPerDeg,
                         limits.max_rad[j] / kRadPerDeg);
    }
    case ArmReason::path_blocked:
      return Error::make(Errc::no_solution, "straight approach blocked %.1f mm before contact",
                         value);
    case ArmReason::bad_request:
      return Error::make(Errc::invalid_argument, "arm plan request outside its domain");
  }
  return Error::make(Errc::invalid_argument, "unknown arm reason");
}

int first_joint_outside(const JointLimits& limits, const JointVector& q, double tolerance_rad) {
  for (int j = 0; j < kJointCount; ++j) {
    if (!(q[j] >= limits.min_rad[j] - tolerance_rad && q[j] <= limits.max_rad[j] + tolerance_rad))
      return j;
  }
  return -1;
}

IkSolution inverse_kinematics(const ArmGeometry& g, const JointLimits& limits,
                              const ToolTarget& target, const JointVector& hint) {
  IkSolution refused;
  if (!finite(target.tip_mm) || !finite(target.axis) || std::abs(target.axis.norm() - 1.0) > 1e-6) {
    refused.reason = ArmReason::bad_target;
    return refused;
  }
  // Into the base frame; renormalise the axis so rounding in the caller does not count.
  const Eigen::Isometry3d base_from_world = g.world_from_base.inverse(Eigen::Isometry);
  const Eigen::Vector3d tip = base_from_world * target.tip_mm;
  const Eigen::Vector3d axis = (base_from_world.linear() * target.axis).normalized();
  // The hand end lies on the tool axis, tool_mm behind the tip, and in the arm's
  // vertical plane through the yaw axis: that plane's azimuth is th1.
  const Eigen::Vector3d hand_end = tip - g.tool_mm * axis;
  const double radial = std::hypot(hand_end.x(), hand_end.y());
  const double th1 = radial > 1e-9 ? std::atan2(hand_end.y(), hand_end.x()) : hint[0];

  // Branches: th1 from the hand end's azimuth (primary) and th1 + pi (reaching
  // back over the base), each with the elbow bent either way. The refusal
  // reported is the primary azimuth's: it is where the target actually lies.
  IkSolution best;
  bool have_best = false;
  IkSolution best_failure;
  bool have_failure = false;
  const double yaws[2] = {th1, th1 + kPi};
  for (int y = 0; y < 2; ++y) {
    for (const double elbow : {1.0, -1.0}) {
      const IkSolution s = solve_branch(g, limits, hand_end, axis, yaws[y], elbow);
      if (s.ok()) {
        if (!have_best || joint_distance(s.q, hint) < joint_distance(best.q, hint)) best = s;
        have_best = true;
        continue;
      }
      if (y != 0) continue;
      // A branch that got as far as the limit check beats one out of reach; among
      // limit failures, the smallest excursion wins.
      bool better = !have_failure;
      if (have_failure) {
        const bool s_limit = s.reason == ArmReason::joint_limit;
        const bool b_limit = best_failure.reason == ArmReason::joint_limit;
        if (s_limit && !b_limit) better = true;
        if (s_limit && b_limit)
          better = limit_excess(limits, s.q) < limit_excess(limits, best_failure.q);
      }
      if (better) best_failure = s;
      have_failure = true;
    }
  }
  return have_best ? best : best_failure;
}

}  // namespace petra::arm
