#include "sim/stereo/stereo_tool.hpp"

#include <algorithm>
#include <chrono>
#include <vector>

#include "algo/camera/calib_json.hpp"
#include "algo/camera/rectify.hpp"
#include "algo/stereo/match_graphcut_bands.hpp"
#include "algo/stereo/shadow.hpp"
#include "sim/eval/disparity_image.hpp"
#include "sim/io/image_io.hpp"
#include "sim/io/parse_roi.hpp"

namespace petra::stereo {

namespace {

// Shadow mask of one view over `area`, threshold from `histogram_roi`.
Status make_mask(ConstGray8View img, Rect histogram_roi, Rect area, double p,
                 std::vector<std::uint8_t>& pixels, ShadowMask& mask) {
  auto t = shadow_threshold(img, histogram_roi, p);
  if (!t) return t.error();
  pixels.assign(static_cast<std::size_t>(area.w) * area.h, 0);
  auto n = shadow_mask(img, area, t->threshold, Gray8View(pixels.data(), area.w, area.h));
  if (!n) return n.error();
  mask.mask = ImageView<const std::uint8_t>(pixels.data(), area.w, area.h);
  mask.area = area;
  return ok_status();
}

}  // namespace

Result<StereoToolReport> run_stereo_tool(const StereoToolOptions& o) {
  if (o.method != "dp" && o.method != "gc")
    return Error::make(Errc::invalid_argument, "--method %s: expected dp or gc", o.method.c_str());
  if (o.out.empty()) return Error::make(Errc::missing_field, "--out: no output file given");
  auto left = io::read_gray_image(o.left);
  if (!left) return left.error();
  auto right = io::read_gray_image(o.right);
  if (!right) return right.error();
  if (left->width != right->width || left->height != right->height)
    return Error::make(Errc::invalid_argument, "left image is %dx%d but right image is %dx%d",
                       left->width, left->height, right->width, right->height);
  const int W = left->width, H = left->height;
  Rect roi{0, 0, W, H};
  if (!o.roi.empty()) {
    auto r = io::parse_roi(o.roi);
    if (!r) return r.error();
    roi = *r;
  }
  if (!roi.inside(W, H))
    return Error::make(Errc::out_of_range, "--roi %d,%d,%d,%d is outside the %dx%d image", roi.x,
                       roi.y, roi.w, roi.h, W, H);

  io::GrayImage rl, rr;  // the pair the matcher sees
  if (!o.calib.empty()) {
    auto text = io::read_text_file(o.calib);
    if (!text) return text.error();
    auto rig = parse_calib_json(*text);
    if (!rig) return rig.error();
    if (rig->left.width != W || rig->left.height != H)
      return Error::make(Errc::invalid_argument,
                         "calibration is for %dx%d images, the pair is %dx%d", rig->left.width,
                         rig->left.height, W, H);
    std::vector<RemapEntry> tl(Rectifier::table_entries(W, H)), tr(tl.size());
    auto rect = Rectifier::create(*rig, tl, tr);
    if (!rect) return rect.error();
    rl = io::GrayImage(W, H);
    rr = io::GrayImage(W, H);
    PETRA_TRY(rect->rectify(StereoSide::left, left->view(), rl.view()));
    PETRA_TRY(rect->rectify(StereoSide::right, right->view(), rr.view()));
    auto mapped = rect->roi_to_rectified(StereoSide::left, roi);
    if (!mapped) return mapped.error();
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
    PETRA_TRY(make_mask(in.left, roi, roi, o.shadow_fraction, mask_l, shadow_l));
    in.left_shadow = &shadow_l;
    const RightShadowWindows windows = right_shadow_windows(roi, o.disp_min, o.disp_max, W);
    if (!windows.mask.empty()) {
      PETRA_TRY(make_mask(in.right, windows.histogram, windows.mask, o.shadow_fraction, mask_r,
                          shadow_r));
      in.right_shadow = &shadow_r;
    }
  }

  // A ground tool sizes its budget for the problem it is given.
  const int count = std::max(o.disp_max - o.disp_min + 1, 1);
  std::vector<std::int16_t> q4(static_cast<std::size_t>(roi.w) * roi.h);
  std::vector<std::uint8_t> conf(q4.size());
  DisparityMap map{ImageView<std::int16_t>(q4.data(), roi.w, roi.h), roi};
  StereoToolReport report;
  const auto t0 = std::chrono::steady_clock::now();
  if (o.method == "dp") {
    MatchDpParams params;
    params.disp_min = o.disp_min;
    params.disp_max = o.disp_max;
    params.edge_constraint = o.edge_constraint;
    const MatchBudget budget{roi.w, roi.h, count};
    std::vector<std::byte> scratch(match_dp_scratch_bytes(budget));
    Arena arena(scratch);
    auto stats = match_dp(in, roi, params, budget, arena, map,
                          ImageView<std::uint8_t>(conf.data(), roi.w, roi.h));
    if (!stats) return stats.error();
    report.stats = *stats;
    report.matched = stats->matched;
  } else {
    if (o.disp_min > o.disp_max)
      return Error::make(Errc::invalid_argument, "--disp-min %d > --disp-max %d: empty range",
                         o.disp_min, o.disp_max);
    GraphCutParams params;
    params.disp_min = o.disp_min;
    params.disp_max = o.disp_max;
    const GraphCutBudget budget{roi.w, roi.h, count};
    const GraphCutBands bands{o.gc_band_rows, 16};
    std::vector<std::byte> block(graph_cut_bands_bytes(budget, bands));
    Arena arena(block);
    auto graph = match_graph_cut_bands(in, roi, params, bands, arena, map);
    if (!graph) return graph.error();
    report.graph = *graph;
    report.matched = graph->matched_pixels;
    // The graph cut has no confidence measure: matched pixels are 255.
    for (std::size_t i = 0; i < q4.size(); ++i) conf[i] = is_valid_disparity(q4[i]) ? 255 : 0;
  }
  const auto t1 = std::chrono::steady_clock::now();

  io::FloatImage disp = eval::to_float_image(map, W, H);
  if (o.fill) eval::fill_invalid_background(disp.view(), roi);
  PETRA_TRY(io::write_pfm(o.out, disp.view()));
  if (!o.confidence.empty()) {
    io::GrayImage c(W, H, 0);
    copy_pixels(ImageView<const std::uint8_t>(conf.data(), roi.w, roi.h), c.view().sub(roi));
    PETRA_TRY(io::write_png(o.confidence, c.view()));
  }
  report.roi = roi;
  report.match_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
  return report;
}

}  // namespace petra::stereo
