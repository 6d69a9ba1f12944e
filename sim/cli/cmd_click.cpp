// `petra click --calib C --uv u,v [--left L --right R]`: the operator's click
// in the left image transferred to the right one (the paper's u2^T F u1 = 0).
// Prints F, the epipolar line (ideal pixels) and its curve in the right image
// (real pixels, distortion applied) at depths along the ray; given the two
// images, the best match along the curve (ZNCC) and the 3D point.
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>

#include "algo/camera/calib_json.hpp"
#include "algo/camera/epipolar.hpp"
#include "sim/cli/commands.hpp"
#include "sim/io/image_io.hpp"

namespace petra::cli {

namespace {

struct ClickArgs {
  std::string calib, uv, left, right;
  int half_window = 7;
  double min_depth_mm = 0;  // 0: three baselines
  double max_depth_mm = 0;  // 0: infinity
};

bool parse_uv(const std::string& text, Eigen::Vector2d& uv) {
  char* end = nullptr;
  const double u = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != ',') return false;
  const char* start = end + 1;
  const double v = std::strtod(start, &end);
  if (end == start || *end != '\0' || !std::isfinite(u) || !std::isfinite(v)) return false;
  uv = {u, v};
  return true;
}

int run(const ClickArgs& a) {
  Eigen::Vector2d click;
  if (!parse_uv(a.uv, click))
    return fail("click", ("--uv: expected u,v in pixels (got '" + a.uv + "')").c_str());
  if (a.left.empty() != a.right.empty())
    return fail("click", "give both --left and --right, or neither");
  auto text = io::read_text_file(a.calib);
  if (!text) return fail("click", text.error().message);
  auto rig = parse_calib_json(*text);
  if (!rig) return fail("click", (a.calib + ": " + rig.error().message).c_str());
  const TsaiCamera& l = rig->left;
  if (!(click.x() >= 0 && click.y() >= 0 && click.x() <= l.width - 1 && click.y() <= l.height - 1))
    return fail("click", "--uv: outside the left image");
  auto f = fundamental_matrix(*rig);
  if (!f) return fail("click", f.error().message);
  // The searched depth range, checked before anything is printed (with or
  // without images: a bad option is refused either way).
  const double baseline = (camera_centre_world(rig->right) - camera_centre_world(l)).norm();
  if (a.min_depth_mm < 0) return fail("click", "--min-depth: must be > 0 mm");
  if (a.max_depth_mm < 0) return fail("click", "--max-depth: must be > 0 mm");
  ClickOptions o;
  o.half_window = a.half_window;
  o.min_depth_mm = a.min_depth_mm > 0 ? a.min_depth_mm : 3 * baseline;
  if (a.max_depth_mm > 0) o.max_depth_mm = a.max_depth_mm;
  if (!(o.max_depth_mm > o.min_depth_mm))
    return fail("click", "--max-depth must exceed --min-depth");

  const Eigen::Vector2d ideal = ideal_pixel(l, click);
  std::printf("left pixel (%.2f, %.2f), ideal (undistorted) (%.2f, %.2f)\n", click.x(), click.y(),
              ideal.x(), ideal.y());
  std::printf("F (ideal pixels, [u2 v2 1] F [u1 v1 1]^T = 0):\n");
  for (int r = 0; r < 3; ++r)
    std::printf("  % .9e % .9e % .9e\n", (*f)(r, 0), (*f)(r, 1), (*f)(r, 2));
  const Eigen::Vector3d line = epipolar_line(*f, ideal);
  std::printf("epipolar line in the right image (ideal pixels): %.6f u + %.6f v + %.4f = 0\n",
              line.x(), line.y(), line.z());
  std::printf(
      "epipolar curve in the right image (pixels, distortion applied), by depth along the left "
      "ray:\n");
  for (double k : {3.0, 5.0, 10.0, 20.0, 50.0, 100.0, 1000.0}) {
    auto r = right_pixel_at_depth(*rig, click, k * baseline);
    if (!r) {
      std::printf("  depth %10.2f mm: not visible (%s)\n", k * baseline, r.error().message);
      continue;
    }
    const bool inside = r->x() >= 0 && r->y() >= 0 && r->x() <= rig->right.width - 1 &&
                        r->y() <= rig->right.height - 1;
    std::printf("  depth %10.2f mm: (%.2f, %.2f)%s\n", k * baseline, r->x(), r->y(),
                inside ? "" : " outside the image");
  }
  if (a.left.empty()) return 0;

  auto left_img = io::read_gray_image(a.left);
  if (!left_img) return fail("click", left_img.error().message);
  auto right_img = io::read_gray_image(a.right);
  if (!right_img) return fail("click", right_img.error().message);
  auto m = transfer_click(*rig, left_img->view(), right_img->view(), click, o);
  if (!m) return fail("click", m.error().message);
  std::printf(
      "match in the right image: (%.2f, %.2f), ZNCC %.3f (best elsewhere %.3f), %d positions "
      "searched\n",
      m->right_px.x(), m->right_px.y(), m->score, m->runner_up, m->samples);
  std::printf(
      "3D point (world frame of %s): (%.3f, %.3f, %.3f) mm, depth %.3f mm, rays %.3f mm apart\n",
      a.calib.c_str(), m->point_mm.x(), m->point_mm.y(), m->point_mm.z(), m->depth_mm,
      m->ray_gap_mm);
  if (m->at_search_end)
    std::printf(
        "warning: the best position is at an end of the searched depth range (%.2f to %.4g mm); "
        "the match may lie outside it: widen --min-depth / --max-depth\n",
        o.min_depth_mm, o.max_depth_mm);
  if (m->score < 0.7 || m->runner_up > m->score - 0.05)
    std::printf(
        "warning: weak or ambiguous match (ZNCC %.3f, next best %.3f); check it in the images\n",
        m->score, m->runner_up);
  return 0;
}

}  // namespace

void add_click(CLI::App& app, Outcome& outcome) {
  auto* cmd = app.add_subcommand(
      "click", "Transfer a left-image click to the right image (epipolar line, match, 3D)");
  static ClickArgs args;
  cmd->add_option("--calib", args.calib, "calib.json (Tsai RAC, mm)")->required();
  cmd->add_option("--uv", args.uv, "the click in the left image: u,v pixels")->required();
  cmd->add_option("--left", args.left, "left image: with --right, search the match");
  cmd->add_option("--right", args.right, "right image");
  cmd->add_option("--window", args.half_window, "correlation half window, px (1..15)")
      ->capture_default_str();
  cmd->add_option("--min-depth", args.min_depth_mm,
                  "nearest depth searched, mm (default: 3 baselines)");
  cmd->add_option("--max-depth", args.max_depth_mm,
                  "farthest depth searched, mm (default: no limit)");
  cmd->callback([&outcome] {
    try {
      outcome.exit_code = run(args);
    } catch (const std::exception& e) {
      outcome.exit_code = fail("click", e.what());
    }
  });
}

}  // namespace petra::cli
