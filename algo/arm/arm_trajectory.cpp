#include "algo/arm/arm_trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace petra::arm {

namespace {

// Between neighbouring path checks (at most 500 mm / 65 = 7.7 mm apart) the
// joints move a few hundredths of a radian; a jump this large is a branch flip.
constexpr double kMaxStepRad = 0.25;
constexpr double kMaxStandoffMm = 500.0;
constexpr double kRadToDeg = 180.0 / std::numbers::pi;
// Joint limits are used at 90 %: the straight line's joint curvature adds a
// small acceleration term the speed choice does not model.
constexpr double kRateMargin = 0.9;

bool positive_finite(double v) {
  return std::isfinite(v) && v > 0.0;
}

std::size_t sample_count(double duration_s, double dt_s) {
  if (!(dt_s > 0.0) || !std::isfinite(duration_s)) return 0;
  return static_cast<std::size_t>(std::ceil(duration_s / dt_s - 1e-9)) + 1;
}

ApproachPlan refuse(ApproachStage stage, ArmReason reason, double value = 0.0) {
  ApproachPlan p;
  p.stage = stage;
  p.refusal.reason = reason;
  p.refusal.value = value;
  return p;
}

ApproachPlan refuse(ApproachStage stage, const IkSolution& s) {
  ApproachPlan p;
  p.stage = stage;
  p.refusal = s;
  return p;
}

}  // namespace

UnitProfile unit_profile(double max_rate, double max_accel) {
  UnitProfile p;
  if (!positive_finite(max_rate) || !positive_finite(max_accel)) return p;
  p.accel = max_accel;
  if (max_rate * max_rate / max_accel >= 1.0) {
    // Triangle: accelerate over half the distance, then brake.
    p.accel_time_s = std::sqrt(1.0 / max_accel);
    p.peak_rate = max_accel * p.accel_time_s;
    p.duration_s = 2.0 * p.accel_time_s;
  } else {
    p.accel_time_s = max_rate / max_accel;
    p.peak_rate = max_rate;
    p.duration_s = 1.0 / max_rate + p.accel_time_s;
  }
  return p;
}

double UnitProfile::position(double t) const {
  if (duration_s <= 0.0 || t >= duration_s) return 1.0;
  if (t <= 0.0) return 0.0;
  const double ta = accel_time_s;
  if (t < ta) return 0.5 * accel * t * t;
  const double rest = duration_s - t;
  if (rest < ta) return 1.0 - 0.5 * accel * rest * rest;
  return 0.5 * accel * ta * ta + peak_rate * (t - ta);
}

double UnitProfile::rate(double t) const {
  if (duration_s <= 0.0 || t <= 0.0 || t >= duration_s) return 0.0;
  const double ta = accel_time_s;
  if (t < ta) return accel * t;
  const double rest = duration_s - t;
  if (rest < ta) return accel * rest;
  return peak_rate;
}

JointVector JointMove::position_at(double t_s) const {
  return from + profile.position(t_s) * delta;
}
JointVector JointMove::velocity_at(double t_s) const {
  return profile.rate(t_s) * delta;
}

Result<JointMove> plan_joint_move(const JointVector& from, const JointVector& to,
                                  const JointLimits& limits) {
  PETRA_TRY(validate_limits(limits));
  if (!from.allFinite())
    return Error::make(Errc::invalid_argument, "joint move: start pose not finite");
  if (!to.allFinite())
    return Error::make(Errc::invalid_argument, "joint move: goal pose not finite");
  const int bad = first_joint_outside(limits, to);
  if (bad >= 0) {
    return Error::make(
        Errc::out_of_range, "joint move: goal th%d = %.2f deg outside %.1f..%.1f deg", bad + 1,
        to[bad] * kRadToDeg, limits.min_rad[bad] * kRadToDeg, limits.max_rad[bad] * kRadToDeg);
  }
  JointMove m;
  m.from = from;
  m.delta = to - from;
  // The common law s(t) moves joint j by delta_j * s: its rate and acceleration
  // bounds become bounds on s' and s''; the tightest joint sets them.
  double max_rate = 0.0;
  double max_accel = 0.0;
  bool moving = false;
  for (int j = 0; j < kJointCount; ++j) {
    const double d = std::abs(m.delta[j]);
    if (d < 1e-12) continue;
    const double r = limits.max_velocity_rad_s[j] / d;
    const double a = limits.max_acceleration_rad_s2[j] / d;
    max_rate = moving ? std::min(max_rate, r) : r;
    max_accel = moving ? std::min(max_accel, a) : a;
    moving = true;
  }
  if (moving) m.profile = unit_profile(max_rate, max_accel);
  return m;
}

std::size_t joint_move_sample_count(const JointMove& move, double dt_s) {
  return sample_count(move.duration_s(), dt_s);
}

Result<std::size_t> sample_joint_move(const JointMove& move, double dt_s,
                                      std::span<JointVector> out) {
  if (!positive_finite(dt_s))
    return Error::make(Errc::non_positive, "joint move: dt must be > 0 s (got %g)", dt_s);
  const std::size_t n = joint_move_sample_count(move, dt_s);
  if (n > out.size()) {
    return Error::make(Errc::capacity_exceeded, "joint move: %zu samples needed, buffer holds %zu",
                       n, out.size());
  }
  for (std::size_t k = 0; k + 1 < n; ++k) out[k] = move.position_at(static_cast<double>(k) * dt_s);
  out[n - 1] = move.from + move.delta;
  return n;
}

const char* approach_stage_name(ApproachStage stage) {
  switch (stage) {
    case ApproachStage::request:
      return "request";
    case ApproachStage::standoff:
      return "standoff";
    case ApproachStage::contact:
      return "contact";
    case ApproachStage::path:
      return "path";
  }
  return "unknown";
}

Error ApproachPlan::error(const JointLimits& limits) const {
  if (ok()) return Error{};
  const Error inner = refusal.error(limits);
  return Error::make(inner.code, "approach %s: %s", approach_stage_name(stage), inner.message);
}

ApproachPlan plan_approach(const ArmGeometry& g, const JointLimits& limits,
                           const ApproachRequest& req, const JointVector& current) {
  if (!validate_geometry(g).ok() || !validate_limits(limits).ok() || !current.allFinite()) {
    return refuse(ApproachStage::request, ArmReason::bad_request);
  }
  if (!req.centroid_mm.allFinite() || !req.normal.allFinite() ||
      std::abs(req.normal.norm() - 1.0) > 1e-3) {
    return refuse(ApproachStage::request, ArmReason::bad_target);
  }
  if (!positive_finite(req.standoff_mm) || req.standoff_mm > kMaxStandoffMm) {
    return refuse(ApproachStage::request, ArmReason::bad_request, req.standoff_mm);
  }
  if (!positive_finite(req.max_tool_speed_mm_s) || !positive_finite(req.max_tool_accel_mm_s2)) {
    return refuse(ApproachStage::request, ArmReason::bad_request);
  }
  const Eigen::Vector3d n = req.normal.normalized();
  ApproachPlan plan;
  StraightApproach& a = plan.approach;
  a.contact = {req.centroid_mm, -n};
  a.standoff = {req.centroid_mm + req.standoff_mm * n, -n};
  a.length_mm = req.standoff_mm;

  const IkSolution at_standoff = inverse_kinematics(g, limits, a.standoff, current);
  if (!at_standoff.ok()) return refuse(ApproachStage::standoff, at_standoff);
  a.standoff_q = at_standoff.q;
  const IkSolution at_contact = inverse_kinematics(g, limits, a.contact, a.standoff_q);
  if (!at_contact.ok()) return refuse(ApproachStage::contact, at_contact);
  a.contact_q = at_contact.q;

  // Walk the line from standoff to contact; record how fast each joint turns per mm.
  JointVector prev = a.standoff_q;
  Eigen::Matrix<double, kJointCount, 1> rad_per_mm = Eigen::Matrix<double, kJointCount, 1>::Zero();
  const double step_mm = a.length_mm / (kPathChecks + 1);
  for (int k = 1; k <= kPathChecks + 1; ++k) {
    const double s_mm = step_mm * k;
    JointVector q;
    if (k == kPathChecks + 1) {
      q = a.contact_q;
    } else {
      const IkSolution s = inverse_kinematics(g, limits, {a.standoff.tip_mm - s_mm * n, -n}, prev);
      if (!s.ok()) {
        ApproachPlan p = refuse(ApproachStage::path, s);
        if (s.reason != ArmReason::joint_limit) p.refusal.value = a.length_mm - s_mm;
        return p;
      }
      q = s.q;
    }
    const JointVector dq = (q - prev).cwiseAbs();
    if (dq.maxCoeff() > kMaxStepRad) {
      return refuse(ApproachStage::path, ArmReason::path_blocked, a.length_mm - s_mm);
    }
    rad_per_mm = rad_per_mm.cwiseMax(dq / step_mm);
    prev = q;
  }
  // Tool speed: the tightest of the request and every joint's rate limits.
  double speed = req.max_tool_speed_mm_s;
  double accel = req.max_tool_accel_mm_s2;
  for (int j = 0; j < kJointCount; ++j) {
    if (rad_per_mm[j] <= 0.0) continue;
    speed = std::min(speed, kRateMargin * limits.max_velocity_rad_s[j] / rad_per_mm[j]);
    accel = std::min(accel, kRateMargin * limits.max_acceleration_rad_s2[j] / rad_per_mm[j]);
  }
  a.tool_speed_mm_s = speed;
  a.tool_accel_mm_s2 = accel;
  a.profile = unit_profile(speed / a.length_mm, accel / a.length_mm);
  return plan;
}

ToolTarget approach_target_at(const StraightApproach& a, double t_s, bool reverse) {
  const double t = std::clamp(t_s, 0.0, a.duration_s());
  double s = a.profile.position(t);
  if (reverse) s = 1.0 - s;
  return {a.standoff.tip_mm + s * (a.contact.tip_mm - a.standoff.tip_mm), a.contact.axis};
}

IkSolution approach_joints_at(const ArmGeometry& g, const JointLimits& limits,
                              const StraightApproach& a, double t_s, const JointVector& hint,
                              bool reverse) {
  return inverse_kinematics(g, limits, approach_target_at(a, t_s, reverse), hint);
}

std::size_t approach_sample_count(const StraightApproach& a, double dt_s) {
  return sample_count(a.duration_s(), dt_s);
}

Result<std::size_t> sample_approach(const ArmGeometry& g, const JointLimits& limits,
                                    const StraightApproach& a, double dt_s,
                                    std::span<JointVector> out) {
  if (!positive_finite(dt_s))
    return Error::make(Errc::non_positive, "approach: dt must be > 0 s (got %g)", dt_s);
  const std::size_t n = approach_sample_count(a, dt_s);
  if (n > out.size()) {
    return Error::make(Errc::capacity_exceeded, "approach: %zu samples needed, buffer holds %zu", n,
                       out.size());
  }
  JointVector hint = a.standoff_q;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = k + 1 == n ? a.duration_s() : static_cast<double>(k) * dt_s;
    const IkSolution s = approach_joints_at(g, limits, a, t, hint);
    if (!s.ok()) return s.error(limits);
    out[k] = s.q;
    hint = s.q;
  }
  return n;
}

}  // namespace petra::arm
