#include "sim/scene/scene_render.hpp"

#include <cmath>
#include <filesystem>
#include <system_error>
#include <vector>

#include "algo/camera/calib_json.hpp"

namespace petra::sim {

namespace {

// The scene, its rectified truth and truth; the views are the caller's.
Result<SceneProducts> scene_and_truth(const SceneOptions& options) {
  auto scene = make_scene(options);
  if (!scene) return scene.error();
  SceneProducts p;
  p.scene = std::move(*scene);
  auto rect = render_rectified_truth(p.scene);
  if (!rect) return rect.error();
  p.rectified = std::move(*rect);
  p.truth = compute_truth(p.scene, p.rectified);
  return p;
}

Status format_texts(SceneProducts& p) {
  std::vector<char> buf(16384);
  auto n = format_calib_json(p.scene.calib_rig, {buf.data(), buf.size()});
  if (!n) return n.error();
  p.calib_json.assign(buf.data(), *n);
  auto truth = format_truth_json(p.scene, p.truth);
  if (!truth) return truth.error();
  p.truth_json = std::move(*truth);
  return {};
}

}  // namespace

Result<SceneProducts> render_scene(const SceneOptions& options) {
  auto p = scene_and_truth(options);
  if (!p) return p.error();
  p->left = render_view(p->scene, Eye::left);
  p->right = render_view(p->scene, Eye::right);
  PETRA_TRY(format_texts(*p));
  return p;
}

Result<SceneProducts> render_scene_roi_window(const SceneOptions& options, int margin) {
  auto p = scene_and_truth(options);
  if (!p) return p.error();
  const Rect& roi = p->truth.roi;
  const int d0 = static_cast<int>(std::floor(p->truth.disparity_min));
  const int d1 = static_cast<int>(std::ceil(p->truth.disparity_max));
  const Rect left{roi.x - margin, roi.y - margin, roi.w + 2 * margin, roi.h + 2 * margin};
  const Rect right{left.x - d1, left.y, left.w + d1 - d0, left.h};
  p->left = render_view(p->scene, Eye::left, left);
  p->right = render_view(p->scene, Eye::right, right);
  PETRA_TRY(format_texts(*p));
  return p;
}

Status prepare_output_dir(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    return Error::make(Errc::io_error, "%s: exists and is not a directory", dir.c_str());
  fs::create_directories(dir, ec);
  if (ec)
    return Error::make(Errc::io_error, "%s: cannot create directory (%s)", dir.c_str(),
                       ec.message().c_str());
  return {};
}

Status write_scene(const SceneProducts& p, const std::string& dir) {
  PETRA_TRY(prepare_output_dir(dir));
  const std::string d = dir + "/";
  PETRA_TRY(io::write_pgm(d + "left.pgm", p.left.image.view()));
  PETRA_TRY(io::write_pgm(d + "right.pgm", p.right.image.view()));
  PETRA_TRY(io::write_png(d + "left.png", p.left.image.view()));
  PETRA_TRY(io::write_png(d + "right.png", p.right.image.view()));
  PETRA_TRY(io::write_text_file(d + "calib.json", p.calib_json));
  PETRA_TRY(io::write_text_file(d + "truth.json", p.truth_json));
  PETRA_TRY(io::write_pfm(d + "disparity_truth.pfm", p.rectified.disparity.view()));
  PETRA_TRY(io::write_pgm(d + "shadow_truth.pgm", p.left.shadow_mask.view()));
  PETRA_TRY(io::write_pgm(d + "shadow_truth_right.pgm", p.right.shadow_mask.view()));
  PETRA_TRY(io::write_pgm(d + "shadow_truth_rectified.pgm", p.rectified.shadow_mask.view()));
  return {};
}

}  // namespace petra::sim
