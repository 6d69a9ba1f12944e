// Angles in the tests: between two directions (deg, exact also for tiny
// angles: atan2 of the cross and dot products), degrees to radians, and the
// arm's joint vectors written in degrees.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "algo/arm/kinematics.hpp"

namespace petra::test {

inline constexpr double kRadPerDeg = std::numbers::pi / 180.0;

inline double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180 / std::numbers::pi;
}

// Five joint angles given in degrees, as the arm's joint vector (radians).
inline arm::JointVector joints_deg(double a, double b, double c, double d, double e) {
  arm::JointVector q;
  q << a * kRadPerDeg, b * kRadPerDeg, c * kRadPerDeg, d * kRadPerDeg, e * kRadPerDeg;
  return q;
}

}  // namespace petra::test
