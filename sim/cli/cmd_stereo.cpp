// `petra stereo`: match a stereo pair with the onboard matcher and write the
// left-view disparity as a Middlebury PFM (docs/icd.md). With --calib the
// pair is rectified first and the ROI (given in the original left image) is
// mapped into the rectified frame; the PFM is in rectified coordinates.
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "algo/calib_json.hpp"
#include "algo/match_dp.hpp"
#include "algo/rectify.hpp"
#include "algo/shadow.hpp"
#include "sim/cli/commands.hpp"
#include "sim/io/parse_roi.hpp"
#include "sim/eval/disparity_image.hpp"
#include "sim/io/image_io.hpp"

namespace petra::cli {

namespace {

struct StereoOptions {
  std::string left, right, method = "dp", roi, calib, out, confidence;
  int disp_min = 0, disp_max = 0;
  double shadow_fraction = 0.0;
  bool fill = false;
  bool no_edges = false;
};

// Shadow mask of one view over `area`, threshold from `histogram_roi`.
Result<long> make_mask(ConstGray8View img, Rect histogram_roi, Rect area, double p,
                       std::vector<std::uint8_t>& pixels, ShadowMask& mask) {
  auto t = shadow_threshold(img, histogram_roi, p);
  if (!t) return t.error();
  pixels.assign(static_cast<std::size_t>(area.w) * area.h, 0);
  auto n = shadow_mask(img, area, t->threshold, Gray8View(pixels.data(), area.w, area.h));
  if (!n) return n.error();
  mask.mask = ImageView<const std::uint8_t>(pixels.data(), area.w, area.h);
  mask.area = area;
  return *n;
}

int run(const StereoOptions& o) {
  if (o.method == "gc")
    return fail("stereo", "--method gc: the graph-cut matcher is not available in this build (use dp)");
  auto left = io::read_gray_image(o.left);
  if (!left) return fail("stereo", left.error().message);
  auto right = io::read_gray_image(o.right);
  if (!right) return fail("stereo", right.error().message);
  if (left->width != right->width || left->height != right->height) {
    char msg[160];
    std::snprintf(msg, sizeof msg, "left image is %dx%d but right image is %dx%d", left->width,
                  left->height, right->width, right->height);
    return fail("stereo", msg);
  }
  const int W = left->width, H = left->height;
  Rect roi{0, 0, W, H};
  if (!o.roi.empty()) {
    auto r = io::parse_roi(o.roi);
    if (!r) return fail("stereo", r.error().message);
    roi = *r;
  }

  io::GrayImage rl, rr;  // the pair the matcher sees
  if (!o.calib.empty()) {
    auto text = io::read_text_file(o.calib);
    if (!text) return fail("stereo", text.error().message);
    auto rig = parse_calib_json(*text);
    if (!rig) return fail("stereo", rig.error().message);
    if (rig->left.width != W || rig->left.height != H) {
      char msg[160];
      std::snprintf(msg, sizeof msg, "calibration is for %dx%d images, the pair is %dx%d",
                    rig->left.width, rig->left.height, W, H);
      return fail("stereo", msg);
    }
    std::vector<RemapEntry> tl(Rectifier::table_entries(W, H)), tr(tl.size());
    auto rect = Rectifier::create(*rig, tl, tr);
    if (!rect) return fail("stereo", rect.error().message);
    rl = io::GrayImage(W, H);
    rr = io::GrayImage(W, H);
    Status s = rect->rectify(StereoSide::left, left->view(), rl.view());
    if (s.ok()) s = rect->rectify(StereoSide::right, right->view(), rr.view());
    if (!s.ok()) return fail("stereo", s.error().message);
    auto mapped = rect->roi_to_rectified(StereoSide::left, roi);
    if (!mapped) return fail("stereo", mapped.error().message);
    roi = *mapped;
  } else {
    rl = std::move(*left);
    rr = std::move(*right);
  }

  StereoInput in;
  in.left = rl.view();
  in.right = rr.view();
  std::vector<std::uint8_t> mask_l, mask_r;
  ShadowMask shadow_l, shadow_r;
  if (o.shadow_fraction != 0.0) {
    if (!roi.inside(W, H)) return fail("stereo", "ROI is outside the image");
    auto nl = make_mask(in.left, roi, roi, o.shadow_fraction, mask_l, shadow_l);
    if (!nl) return fail("stereo", nl.error().message);
    const Rect area = right_search_area(roi, o.disp_min, o.disp_max, W);
    if (!area.empty()) {
      // The right histogram covers an ROI-sized window at the middle disparity.
      Rect hist = roi;
      hist.x = std::clamp(roi.x - (o.disp_min + o.disp_max) / 2, 0, W - roi.w);
      auto nr = make_mask(in.right, hist, area, o.shadow_fraction, mask_r, shadow_r);
      if (!nr) return fail("stereo", nr.error().message);
      in.right_shadow = &shadow_r;
    }
    in.left_shadow = &shadow_l;
  }

  MatchDpParams params;
  params.disp_min = o.disp_min;
  params.disp_max = o.disp_max;
  params.edge_constraint = !o.no_edges;
  // The ground tool sizes its budget for the problem it is given.
  MatchBudget budget{std::max(roi.w, 1), std::max(roi.h, 1),
                     std::max(o.disp_max - o.disp_min + 1, 1)};
  std::vector<std::byte> scratch(match_dp_scratch_bytes(budget));
  Arena arena(scratch);
  std::vector<std::int16_t> q4(static_cast<std::size_t>(std::max(roi.w, 0)) * std::max(roi.h, 0));
  std::vector<std::uint8_t> conf(q4.size());
  DisparityMap map{ImageView<std::int16_t>(q4.data(), std::max(roi.w, 0), std::max(roi.h, 0)), roi};
  const auto t0 = std::chrono::steady_clock::now();
  auto stats = match_dp(in, roi, params, budget, arena, map,
                        ImageView<std::uint8_t>(conf.data(), std::max(roi.w, 0), std::max(roi.h, 0)));
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (!stats) return fail("stereo", stats.error().message);

  io::FloatImage disp = eval::to_float_image(map, W, H);
  if (o.fill) eval::fill_invalid_background(disp.view(), roi);
  Status s = io::write_pfm(o.out, disp.view());
  if (!s.ok()) return fail("stereo", s.error().message);
  if (!o.confidence.empty()) {
    io::GrayImage c(W, H, 0);
    copy_pixels(ImageView<const std::uint8_t>(conf.data(), roi.w, roi.h), c.view().sub(roi));
    s = io::write_png(o.confidence, c.view());
    if (!s.ok()) return fail("stereo", s.error().message);
  }
  std::printf("stereo: ROI %d,%d %dx%d, disparities %d..%d: %ld of %ld px matched (%.1f%%) in %.1f ms\n",
              roi.x, roi.y, roi.w, roi.h, o.disp_min, o.disp_max, stats->matched, stats->roi_pixels,
              100.0 * static_cast<double>(stats->matched) / static_cast<double>(stats->roi_pixels), ms);
  std::printf("stereo: edges %ld left / %ld right, %ld edge pairs, %ld anchors; rejected: "
              "left-right %ld, uniqueness %ld, cost %ld, range %ld, shadow %ld + %ld\n",
              stats->left_edges, stats->right_edges, stats->edge_pairs, stats->anchors, stats->rejected_lr,
              stats->rejected_uniqueness, stats->rejected_cost, stats->rejected_range, stats->shadow_left,
              stats->rejected_shadow_right);
  return 0;
}

}  // namespace

void add_stereo(CLI::App& app, Outcome& outcome) {
  auto* cmd = app.add_subcommand("stereo", "Match a stereo pair; write the left-view disparity (PFM)");
  static StereoOptions o;
  cmd->add_option("--left", o.left, "left image (PGM, PPM or PNG)")->required();
  cmd->add_option("--right", o.right, "right image")->required();
  cmd->add_option("--method", o.method, "matcher: dp (edge-constrained scanline DP) or gc (graph cut)")
      ->check(CLI::IsMember({"dp", "gc"}));
  cmd->add_option("--disp-min", o.disp_min, "smallest disparity, px (right x = left x - d)")->required();
  cmd->add_option("--disp-max", o.disp_max, "largest disparity, px")->required();
  cmd->add_option("--roi", o.roi, "x,y,w,h in the (original) left image; default: whole image");
  cmd->add_option("--calib", o.calib, "calib.json: rectify the pair first");
  cmd->add_option("--shadow-fraction", o.shadow_fraction, "prior shadow fraction p in [0, 1); 0 = none");
  cmd->add_flag("--fill", o.fill, "fill invalid pixels with the smaller nearest valid disparity on the row");
  cmd->add_option("--out", o.out, "output disparity, Middlebury PFM (invalid = inf)")->required();
  cmd->add_option("--confidence", o.confidence, "optional confidence image (PNG, 0 = invalid)");
  cmd->add_flag("--no-edges", o.no_edges, "skip the edge constraint (for comparisons only)");
  cmd->callback([&outcome] {
    try {
      outcome.exit_code = run(o);
    } catch (const std::exception& e) {
      outcome.exit_code = fail("stereo", e.what());
    }
  });
}

}  // namespace petra::cli
