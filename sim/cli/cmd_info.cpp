// `petra info --calib C`: validates a calib.json and prints the rig in words
// (focal lengths, baseline, distortion) so an operator can sanity-check it.
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

#include "algo/camera/calib_json.hpp"
#include "sim/cli/commands.hpp"
#include "sim/io/image_io.hpp"

namespace petra::cli {

namespace {

void print_camera_summary(const char* name, const TsaiCamera& c) {
  const Eigen::Vector3d centre = camera_centre_world(c);
  const PinholeConversion pin = to_pinhole(c);
  std::printf(
      "%-5s %dx%d px, f %.4f mm (fx %.2f px, fy %.2f px), sx %.5f, principal point (%.2f, %.2f)\n",
      name, c.width, c.height, c.f_mm, pin.pinhole.fx, pin.pinhole.fy, c.sx, c.cx_px, c.cy_px);
  std::printf(
      "      kappa1 %.6g /mm^2 (OpenCV k1 %.5f, fit within %.3f px), pixel %.5f x %.5f mm\n",
      c.kappa1, pin.pinhole.k1, pin.max_error_px, c.dx_mm, c.dy_mm);
  std::printf("      centre in world (%.2f, %.2f, %.2f) mm, optical axis (%.4f, %.4f, %.4f)\n",
              centre.x(), centre.y(), centre.z(), c.R(2, 0), c.R(2, 1), c.R(2, 2));
}

}  // namespace

void add_info(CLI::App& app, Outcome& outcome) {
  auto* cmd = app.add_subcommand("info", "Validate a calib.json and describe the stereo rig");
  static std::string calib_path;
  cmd->add_option("--calib", calib_path, "calib.json (Tsai RAC, mm)")->required();
  cmd->callback([&outcome] {
    auto text = io::read_text_file(calib_path);
    if (!text) {
      outcome.exit_code = fail("info", text.error().message);
      return;
    }
    auto rig = parse_calib_json(*text);
    if (!rig) {
      outcome.exit_code = fail("info", rig.error().message);
      return;
    }
    print_camera_summary("left", rig->left);
    print_camera_summary("right", rig->right);
    const double baseline =
        (camera_centre_world(rig->left) - camera_centre_world(rig->right)).norm();
    const Eigen::Matrix3d rel = rig->right.R * rig->left.R.transpose();
    const double angle_deg = Eigen::AngleAxisd(rel).angle() * 180.0 / M_PI;
    std::printf("rig   baseline %.3f mm, relative rotation %.4f deg\n", baseline, angle_deg);
  });
}

}  // namespace petra::cli
