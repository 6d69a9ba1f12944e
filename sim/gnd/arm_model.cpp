#include "sim/gnd/arm_model.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <vector>

#include "algo/core/json_reader.hpp"
#include "sim/gnd/json_text.hpp"

namespace petra::gnd {

namespace {

constexpr double kMinStandoffMm = 5.0;  // ARM_GOTO's standoff range (docs/icd.md)
constexpr double kMaxStandoffMm = 300.0;

std::string geometry_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  return buf;
}

std::string vec_json(const Eigen::Vector3d& v) {
  return "[" + geometry_number(v.x()) + "," + geometry_number(v.y()) + "," +
         geometry_number(v.z()) + "]";
}

template <std::size_t N>
std::string array_json(const std::array<double, N>& a, double scale = 1.0) {
  std::string s = "[";
  for (std::size_t k = 0; k < N; ++k) s += (k ? "," : "") + geometry_number(a[k] * scale);
  return s + "]";
}

std::string joints_deg_json(const arm::JointVector& q) {
  std::array<double, arm::kJointCount> a{};
  for (int k = 0; k < arm::kJointCount; ++k)
    a[static_cast<std::size_t>(k)] = q[k] / arm::kRadPerDeg;
  return array_json(a);
}

Result<Eigen::Vector3d> read_vec3(const json::Document& doc, const char* name) {
  const std::uint32_t t = doc.find(0, name);
  if (t == 0) return Error::make(Errc::missing_field, "%s: missing", name);
  if (doc.token(t).type != json::Type::array || doc.token(t).count != 3)
    return Error::make(Errc::invalid_argument, "%s: expected [x, y, z]", name);
  Eigen::Vector3d v;
  for (std::uint32_t k = 0; k < 3; ++k) {
    const json::Token& e = doc.token(doc.element(t, k));
    if (e.type != json::Type::number || !std::isfinite(e.number) || std::abs(e.number) > 1e7)
      return Error::make(Errc::invalid_argument, "%s[%u]: expected a number within 1e7", name, k);
    v[static_cast<int>(k)] = e.number;
  }
  return v;
}

}  // namespace

Result<arm::ArmGeometry> parse_arm_mount(std::string_view text) {
  std::array<double, 4> v{};
  std::size_t n = 0;
  std::stringstream ss{std::string(text)};
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (n == 4 || end == item.c_str() || *end != '\0' || !std::isfinite(x) || std::abs(x) > 1e5)
      return Error::make(Errc::invalid_argument,
                         "--arm-mount '%.*s': expected x_mm,y_mm,z_mm,yaw_deg, each within 1e5",
                         static_cast<int>(text.size()), text.data());
    v[n++] = x;
  }
  if (n != 4)
    return Error::make(Errc::invalid_argument, "--arm-mount '%.*s': expected 4 numbers",
                       static_cast<int>(text.size()), text.data());
  arm::ArmGeometry g = arm::rover_arm_geometry();
  g.world_from_base = Eigen::Translation3d(v[0], v[1], v[2]) *
                      Eigen::AngleAxisd(v[3] * arm::kRadPerDeg, Eigen::Vector3d::UnitZ());
  return g;
}

ArmModel::ArmModel(const arm::ArmGeometry& geometry)
    : geometry_(geometry), limits_(arm::default_joint_limits()) {}

std::string ArmModel::skeleton_json(const std::array<double, arm::kJointCount>& joint_deg) const {
  arm::JointVector q;
  for (int k = 0; k < arm::kJointCount; ++k)
    q[k] = joint_deg[static_cast<std::size_t>(k)] * arm::kRadPerDeg;
  const arm::ArmSkeleton s = arm::arm_skeleton(geometry_, q);
  std::string out = "[";
  for (std::size_t k = 0; k < s.points_mm.size(); ++k)
    out += (k ? "," : "") + vec_json(s.points_mm[k]);
  return out + "]";
}

std::string ArmModel::geometry_json() const {
  const Eigen::Vector3d m = geometry_.world_from_base.translation();
  const Eigen::Vector3d x = geometry_.world_from_base.linear().col(0);
  const arm::JointVector stow = arm::stow_pose();
  std::array<double, arm::kJointCount> stow_deg{};
  for (int k = 0; k < arm::kJointCount; ++k)
    stow_deg[static_cast<std::size_t>(k)] = stow[k] / arm::kRadPerDeg;
  std::ostringstream o;
  o << "{\"mount_mm\":" << vec_json(m)
    << ",\"yaw_deg\":" << geometry_number(std::atan2(x.y(), x.x()) / arm::kRadPerDeg)
    << ",\"links_mm\":{\"shoulder_height\":" << geometry_number(geometry_.shoulder_height_mm)
    << ",\"shoulder_offset\":" << geometry_number(geometry_.shoulder_offset_mm)
    << ",\"upper_arm\":" << geometry_number(geometry_.upper_arm_mm)
    << ",\"forearm\":" << geometry_number(geometry_.forearm_mm)
    << ",\"hand\":" << geometry_number(geometry_.hand_mm)
    << ",\"tool\":" << geometry_number(geometry_.tool_mm) << "}"
    << ",\"limits_deg\":{\"min\":" << array_json(limits_.min_rad, 1.0 / arm::kRadPerDeg)
    << ",\"max\":" << array_json(limits_.max_rad, 1.0 / arm::kRadPerDeg) << "}"
    << ",\"stow_deg\":" << array_json(stow_deg) << ",\"stow\":" << skeleton_json(stow_deg) << "}";
  return o.str();
}

Result<std::string> ArmModel::plan_json(
    std::string_view body, const std::array<double, arm::kJointCount>& current_deg) const {
  if (body.size() > 4096)
    return Error::make(Errc::invalid_argument, "request: body of %zu bytes exceeds 4096",
                       body.size());
  std::vector<json::Token> tokens(64);
  auto doc = json::Document::parse(body, tokens);
  if (!doc) return Error::make(Errc::parse_error, "request: not JSON: %s", doc.error().message);
  if (doc->token(0).type != json::Type::object)
    return Error::make(Errc::invalid_argument, "request: must be a JSON object");
  auto centroid = read_vec3(*doc, "centroid_mm");
  if (!centroid) return centroid.error();
  auto normal = read_vec3(*doc, "normal");
  if (!normal) return normal.error();
  if (std::abs(normal->norm() - 1.0) > 0.01)
    return Error::make(Errc::invalid_argument, "normal: length %.4f, expected a unit vector",
                       normal->norm());
  const std::uint32_t s = doc->find(0, "standoff_mm");
  if (s == 0) return Error::make(Errc::missing_field, "standoff_mm: missing");
  const double standoff = doc->token(s).number;
  if (doc->token(s).type != json::Type::number || !(standoff >= kMinStandoffMm) ||
      standoff > kMaxStandoffMm)
    return Error::make(Errc::out_of_range, "standoff_mm: expected %.0f..%.0f mm", kMinStandoffMm,
                       kMaxStandoffMm);

  arm::ApproachRequest r;
  r.centroid_mm = *centroid;
  r.normal = normal->normalized();
  r.standoff_mm = standoff;
  arm::JointVector current;
  for (int k = 0; k < arm::kJointCount; ++k)
    current[k] = current_deg[static_cast<std::size_t>(k)] * arm::kRadPerDeg;
  const arm::ApproachPlan plan = arm::plan_approach(geometry_, limits_, r, current);
  if (!plan.ok())
    return std::string("{\"ok\":false,\"stage\":") +
           json_string(arm::approach_stage_name(plan.stage)) +
           ",\"reason\":" + json_string(plan.error(limits_).message) + "}";
  auto pose = [this](const arm::JointVector& q, const arm::ToolTarget& t) {
    std::array<double, arm::kJointCount> deg{};
    for (int k = 0; k < arm::kJointCount; ++k)
      deg[static_cast<std::size_t>(k)] = q[k] / arm::kRadPerDeg;
    return "{\"joint_deg\":" + joints_deg_json(q) + ",\"skeleton\":" + skeleton_json(deg) +
           ",\"tip_mm\":" + vec_json(t.tip_mm) + ",\"axis\":" + vec_json(t.axis) + "}";
  };
  const arm::StraightApproach& a = plan.approach;
  return "{\"ok\":true,\"standoff\":" + pose(a.standoff_q, a.standoff) +
         ",\"contact\":" + pose(a.contact_q, a.contact) +
         ",\"length_mm\":" + geometry_number(a.length_mm) +
         ",\"duration_s\":" + geometry_number(a.duration_s()) + "}";
}

}  // namespace petra::gnd
