// `petra arm-view`: a picture of the arm reaching a grind plane, as ARM_GOTO
// would plan it (standoff along the normal, straight approach, joint limits).
//   petra arm-view --planes planes.json [--plane N] --out view.png
//   petra arm-view --centroid x,y,z --normal nx,ny,nz [--ground nx,ny,nz,d] --out view.svg
// Options: --standoff MM (50), --mount x,y,z,yaw_deg (the arm base in the world;
// default the rover mount of docs/arm.md), --from th1..th5 deg (start pose,
// default stow). The picture is written also when the plan is refused; then
// the reason goes to stderr and the exit status is 1.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "sim/arm/arm_view.hpp"
#include "sim/cli/commands.hpp"
#include "sim/io/image_io.hpp"

namespace petra::cli {

namespace {

bool parse_numbers(const std::string& text, std::size_t min_n, std::size_t max_n,
                   std::vector<double>& out) {
  out.clear();
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (end == item.c_str() || *end != '\0' || !std::isfinite(v)) return false;
    out.push_back(v);
  }
  return out.size() >= min_n && out.size() <= max_n;
}

bool ends_with(const std::string& s, const char* suffix) {
  const std::string x(suffix);
  return s.size() >= x.size() && s.compare(s.size() - x.size(), x.size(), x) == 0;
}

}  // namespace

void add_arm_view(CLI::App& app, Outcome& outcome) {
  auto* cmd =
      app.add_subcommand("arm-view", "Picture of the arm reaching a grind plane (PNG or SVG)");
  static std::string planes_path, centroid_text, normal_text, ground_text, mount_text, from_text,
      out_path;
  static int plane_number = 1;
  static double standoff_mm = arm::kDefaultStandoffMm;
  auto* planes_opt =
      cmd->add_option("--planes", planes_path, "planes.json (grind planes, world frame)");
  cmd->add_option("--plane", plane_number, "which plane of planes.json, 1 = best (default 1)");
  auto* centroid_opt =
      cmd->add_option("--centroid", centroid_text, "plane centroid x,y,z (mm, world)");
  auto* normal_opt =
      cmd->add_option("--normal", normal_text, "plane normal nx,ny,nz (unit, out of the rock)");
  cmd->add_option("--ground", ground_text,
                  "ground plane nx,ny,nz,d_mm (optional, drawn as a grid)");
  cmd->add_option("--standoff", standoff_mm, "standoff distance along the normal, mm (default 50)");
  cmd->add_option("--mount", mount_text,
                  "arm base in the world: x,y,z,yaw_deg (default: rover mount)");
  cmd->add_option("--from", from_text, "start pose th1..th5, deg (default: stow 0,0,145,35,0)");
  cmd->add_option("--out", out_path, "output picture, .png or .svg")->required();
  centroid_opt->excludes(planes_opt);
  normal_opt->excludes(planes_opt);
  cmd->callback([&outcome] {
    auto bad = [&](const std::string& why) { outcome.exit_code = fail("arm-view", why.c_str()); };
    sim::ArmViewInput in;
    std::vector<double> v;
    if (!planes_path.empty()) {
      auto text = io::read_text_file(planes_path);
      if (!text) return bad(text.error().message);
      auto file = sim::parse_planes_json(*text, planes_path.c_str());
      if (!file) return bad(file.error().message);
      if (plane_number < 1 || plane_number > static_cast<int>(file->planes.size())) {
        return bad("--plane " + std::to_string(plane_number) + ": the file has " +
                   std::to_string(file->planes.size()) + " planes");
      }
      in.planes = file->planes;
      in.chosen = static_cast<std::size_t>(plane_number - 1);
      in.ground = file->ground;
    } else {
      if (centroid_text.empty() || normal_text.empty())
        return bad("give --planes, or --centroid and --normal");
      sim::OutputPlane p;
      if (!parse_numbers(centroid_text, 3, 3, v)) return bad("--centroid: expected x,y,z in mm");
      p.centroid_mm = Eigen::Vector3d(v[0], v[1], v[2]);
      if (!parse_numbers(normal_text, 3, 3, v)) return bad("--normal: expected nx,ny,nz");
      p.normal = Eigen::Vector3d(v[0], v[1], v[2]);
      if (p.normal.norm() < 1e-9) return bad("--normal: zero vector");
      p.normal.normalize();
      in.planes.push_back(p);
    }
    if (!ground_text.empty()) {
      if (!parse_numbers(ground_text, 4, 4, v)) return bad("--ground: expected nx,ny,nz,d_mm");
      const Eigen::Vector3d n(v[0], v[1], v[2]);
      if (n.norm() < 1e-9) return bad("--ground: zero normal");
      in.ground = sim::GroundPlane{n / n.norm(), v[3] / n.norm()};
    }
    if (!mount_text.empty()) {
      if (!parse_numbers(mount_text, 4, 4, v)) return bad("--mount: expected x,y,z,yaw_deg");
      in.geometry.world_from_base =
          Eigen::Translation3d(v[0], v[1], v[2]) *
          Eigen::AngleAxisd(v[3] * arm::kRadPerDeg, Eigen::Vector3d::UnitZ());
    }
    if (!from_text.empty()) {
      if (!parse_numbers(from_text, 5, 5, v)) return bad("--from: expected 5 angles in degrees");
      for (int j = 0; j < 5; ++j) in.start[j] = v[j] * arm::kRadPerDeg;
    }
    if (!(standoff_mm > 0.0)) return bad("--standoff must be > 0 mm");
    in.standoff_mm = standoff_mm;
    auto view = sim::plan_arm_view(in);
    if (!view) return bad(view.error().message);
    constexpr int kWidth = 1400, kHeight = 900;
    const sim::Rgb background{255, 255, 255};
    Status written;
    if (ends_with(out_path, ".svg")) {
      sim::SvgCanvas canvas(kWidth, kHeight, background);
      sim::draw_arm_view(in, *view, canvas);
      written = io::write_text_file(out_path, canvas.finish());
    } else if (ends_with(out_path, ".png")) {
      sim::RasterCanvas canvas(kWidth, kHeight, background);
      sim::draw_arm_view(in, *view, canvas);
      written = io::write_png(out_path, canvas.image());
    } else {
      return bad("--out: the name must end in .png or .svg");
    }
    if (!written) return bad(written.error().message);
    for (const std::string& line : view->summary) std::printf("%s\n", line.c_str());
    std::printf("wrote %s\n", out_path.c_str());
    if (!view->plan.ok()) outcome.exit_code = fail("arm-view", view->plan.error(in.limits).message);
  });
}

}  // namespace petra::cli
