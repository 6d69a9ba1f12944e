// `petra calib --cols 9 --rows 6 --square MM --left 'DIR/left*.jpg'
//  --right 'DIR/right*.jpg' --out calib.json`: Tsai stereo calibration from
// chessboard pairs (sim/calib). Prints every rejected image and why, the RMS
// reprojection error of every image and overall, the intrinsics with their
// uncertainties and the baseline; writes the calib.json contract.
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "algo/camera/calib_json.hpp"
#include "sim/calib/board_images.hpp"
#include "sim/calib/format_text.hpp"
#include "sim/calib/stereo_calibration.hpp"
#include "sim/cli/commands.hpp"
#include "sim/io/image_io.hpp"

namespace petra::cli {

namespace {

struct CalibArgs {
  int cols = 9;
  int rows = 6;
  double square_mm = 0;
  std::string left, right, out;
  std::string pixel_mm = "0.00465";
  bool fix_sx = false;
  bool fix_centre = false;
  std::string world = "left";
};

std::string base(const std::string& p) {
  const std::size_t s = p.find_last_of('/');
  return s == std::string::npos ? p : p.substr(s + 1);
}

bool parse_pitch(const std::string& text, double& dx, double& dy) {
  char* end = nullptr;
  dx = std::strtod(text.c_str(), &end);
  if (end == text.c_str()) return false;
  if (*end == ',') {
    const char* start = end + 1;
    dy = std::strtod(start, &end);
    if (end == start) return false;
  } else {
    dy = dx;
  }
  return *end == '\0' && std::isfinite(dx) && std::isfinite(dy) && dx > 0 && dy > 0;
}

void print_camera(const char* name, const TsaiCamera& c,
                  const std::array<double, calib::kIntrinsicCount>& s,
                  const calib::CameraCalibration& alone) {
  std::printf(
      "%-5s camera: f %.5f +- %.5f mm (fx %.2f px, fy %.2f px), kappa1 %.6g +- %.2g /mm^2\n", name,
      c.f_mm, s[calib::kF], c.f_mm * c.sx / c.dx_mm, c.f_mm / c.dy_mm, c.kappa1, s[calib::kKappa1]);
  std::printf(
      "              principal point (%.2f +- %.2f, %.2f +- %.2f) px, sx %.5f +- %.5f, pixel %.5f "
      "x %.5f mm\n",
      c.cx_px, s[calib::kCx], c.cy_px, s[calib::kCy], c.sx, s[calib::kSx], c.dx_mm, c.dy_mm);
  std::printf("              on its own: RMS %.4f px over %zu views\n", alone.rms_px,
              alone.views.size());
}

int run(const CalibArgs& a) {
  double dx = 0, dy = 0;
  if (!parse_pitch(a.pixel_mm, dx, dy))
    return fail("calib",
                ("--pixel-mm: expected D or DX,DY in mm, > 0 (got '" + a.pixel_mm + "')").c_str());
  if (!(a.square_mm > 0) || !std::isfinite(a.square_mm))
    return fail("calib", "--square must be > 0 (mm)");
  if (a.world != "left" && a.world != "target")
    return fail("calib", "--world must be 'left' or 'target'");
  calib::ChessboardOptions board;
  board.cols = a.cols;
  board.rows = a.rows;
  if (a.cols < 2 || a.rows < 2 || a.cols > 100 || a.rows > 100)
    return fail("calib", "--cols and --rows: inner corners, 2..100 each");
  auto found = calib::find_boards(a.left, a.right, board);
  if (!found) return fail("calib", found.error().message);
  std::printf("board %dx%d inner corners, square %g mm; pixel pitch %g x %g mm\n", a.cols, a.rows,
              a.square_mm, dx, dy);
  for (const calib::RejectedImage& r : found->rejected)
    std::printf("rejected %s: %s\n", r.path.c_str(), r.reason.c_str());
  if (!found->orientation_unique)
    std::printf(
        "warning: a %dx%d board looks the same turned by 180 degrees; left and right corners are "
        "matched "
        "by image position only (use a board with cols + rows odd)\n",
        a.cols, a.rows);

  calib::StereoCalibOptions o;
  o.cols = a.cols;
  o.rows = a.rows;
  o.square_mm = a.square_mm;
  o.left_sensor.width = found->left_width;
  o.left_sensor.height = found->left_height;
  o.right_sensor.width = found->right_width;
  o.right_sensor.height = found->right_height;
  for (TsaiCamera* s : {&o.left_sensor, &o.right_sensor}) {
    s->dx_mm = dx;
    s->dy_mm = dy;
    s->sx = 1;
  }
  o.camera.estimate_sx = !a.fix_sx;
  o.camera.estimate_centre = !a.fix_centre;
  o.world_at_target = a.world == "target";
  auto cal = calib::calibrate_stereo(found->pairs, o);
  if (!cal) return fail("calib", cal.error().message);

  for (const std::string& n : cal->notes) std::printf("note: %s\n", n.c_str());
  std::printf("RMS reprojection error per image (px, joint stereo model):\n");
  for (std::size_t p = 0; p < found->pairs.size(); ++p) {
    const calib::StereoPairCorners& pc = found->pairs[p];
    auto cell = [](double rms) {
      return rms < 0 ? std::string("   -  ") : calib::format_text("%6.3f", rms);
    };
    std::printf("  %-24s %s   %-24s %s\n", base(pc.left_name).c_str(),
                cell(cal->left_rms_px[p]).c_str(), base(pc.right_name).c_str(),
                cell(cal->right_rms_px[p]).c_str());
  }
  print_camera("left", cal->rig.left, cal->left_sigma, cal->left_alone);
  print_camera("right", cal->rig.right, cal->right_sigma, cal->right_alone);
  std::printf("stereo: RMS %.4f px overall (left %.4f, right %.4f) over %zu pairs\n", cal->rms_px,
              cal->left_rms_px_all, cal->right_rms_px_all, cal->pairs.size());
  const Eigen::Matrix3d rel = cal->rig.right.R * cal->rig.left.R.transpose();
  std::printf("baseline %.4f mm (%.4f squares), relative rotation %.3f deg\n", cal->baseline_mm,
              cal->baseline_mm / a.square_mm, Eigen::AngleAxisd(rel).angle() * 180.0 / M_PI);
  if (cal->world_pair >= 0)
    std::printf("world frame: the board in %s\n",
                base(found->pairs[static_cast<std::size_t>(cal->world_pair)].left_name).c_str());
  else
    std::printf("world frame: the left camera\n");

  std::vector<char> buf(16384);
  auto n = format_calib_json(cal->rig, buf);
  if (!n) return fail("calib", n.error().message);
  if (auto s = io::write_text_file(a.out, std::string_view(buf.data(), *n)); !s)
    return fail("calib", s.error().message);
  std::printf("wrote %s\n", a.out.c_str());
  return 0;
}

}  // namespace

void add_calib(CLI::App& app, Outcome& outcome) {
  auto* cmd = app.add_subcommand("calib", "Tsai stereo calibration from chessboard image pairs");
  static CalibArgs args;
  cmd->add_option("--cols", args.cols, "inner corners along the board's first axis")->required();
  cmd->add_option("--rows", args.rows, "inner corners along the second axis")->required();
  cmd->add_option("--square", args.square_mm,
                  "square size in mm (calib.json lengths use this unit)")
      ->required();
  cmd->add_option("--left", args.left, "left images, a quoted pattern such as 'DIR/left*.jpg'")
      ->required();
  cmd->add_option("--right", args.right, "right images, e.g. 'DIR/right*.jpg'")->required();
  cmd->add_option("--out", args.out, "calib.json to write")->required();
  cmd->add_option(
         "--pixel-mm", args.pixel_mm,
         "pixel pitch D or DX,DY in mm (not observable from the images; scales f and kappa1)")
      ->capture_default_str();
  cmd->add_flag("--fix-sx", args.fix_sx, "keep sx = 1 instead of estimating it");
  cmd->add_flag("--fix-centre", args.fix_centre, "keep the principal point at the image centre");
  cmd->add_option("--world", args.world,
                  "world frame: 'left' camera or 'target' (board of the first pair)")
      ->capture_default_str();
  cmd->callback([&outcome] {
    try {
      outcome.exit_code = run(args);
    } catch (const std::exception& e) {
      outcome.exit_code = fail("calib", e.what());
    }
  });
}

}  // namespace petra::cli
