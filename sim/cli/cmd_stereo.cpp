// `petra stereo`: match a stereo pair with the onboard matcher and write the
// left-view disparity as a Middlebury PFM (docs/icd.md). The work is in
// sim/stereo/stereo_tool; this file is the command line.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <string>

#include "algo/core/disparity.hpp"
#include "sim/cli/commands.hpp"
#include "sim/stereo/stereo_tool.hpp"

namespace petra::cli {

namespace {

int run(const stereo::StereoToolOptions& o) {
  auto r = stereo::run_stereo_tool(o);
  if (!r) return fail("stereo", r.error().message);
  const long roi_pixels = static_cast<long>(r->roi.w) * r->roi.h;
  std::printf(
      "stereo: ROI %d,%d %dx%d, disparities %d..%d: %ld of %ld px matched (%.1f%%) in %.1f ms\n",
      r->roi.x, r->roi.y, r->roi.w, r->roi.h, o.disp_min, o.disp_max, r->matched, roi_pixels,
      100.0 * static_cast<double>(r->matched) / static_cast<double>(roi_pixels), r->match_ms);
  if (o.method == "gc") {
    const GraphCutReport& g = r->graph;
    std::printf(
        "stereo: graph cut K %d, lambda1 %d, lambda2 %d; %d cycles (%s), %d expansions; energy "
        "%lld -> %lld; occluded %ld, shadow %ld\n",
        g.occlusion_k, g.lambda1, g.lambda2, g.cycles, g.converged ? "converged" : "cycle limit",
        g.expansions, static_cast<long long>(g.energy_start), static_cast<long long>(g.energy),
        g.occluded_pixels, g.shadow_pixels);
    return 0;
  }
  const MatchDpStats& s = r->stats;
  std::printf(
      "stereo: edges %ld left / %ld right, %ld edge pairs, %ld anchors; rejected: left-right %ld, "
      "uniqueness %ld, cost %ld, range %ld, shadow %ld + %ld; right gray levels x %.3f %+.1f\n",
      s.left_edges, s.right_edges, s.edge_pairs, s.anchors, s.rejected_lr, s.rejected_uniqueness,
      s.rejected_cost, s.rejected_range, s.shadow_left, s.rejected_shadow_right,
      s.gray_gain_q8 / 256.0, s.gray_offset_q8 / 256.0);
  return 0;
}

}  // namespace

// The matchers' disparities are Q4 in int16 (algo/core/disparity.hpp): 2047 px at most.
constexpr int kMaxDisparityPx = std::numeric_limits<std::int16_t>::max() / kDisparityScale;

void add_stereo(CLI::App& app, Outcome& outcome) {
  auto* cmd =
      app.add_subcommand("stereo", "Match a stereo pair; write the left-view disparity (PFM)");
  static stereo::StereoToolOptions o;
  static bool no_edges = false;
  cmd->add_option("--left", o.left, "left image (PGM, PPM or PNG)")->required();
  cmd->add_option("--right", o.right, "right image")->required();
  cmd->add_option("--method", o.method,
                  "matcher: dp (edge-constrained scanline DP) or gc (graph cut)")
      ->check(CLI::IsMember({"dp", "gc"}));
  cmd->add_option("--disp-min", o.disp_min, "smallest disparity, px (right x = left x - d)")
      ->required();
  cmd->add_option("--disp-max", o.disp_max, "largest disparity, px")->required();
  cmd->add_option("--gc-band-rows", o.gc_band_rows,
                  "gc: match in bands of this many rows (+16 above and below), as petra-fsw does; "
                  "0: whole ROI");
  cmd->add_option("--roi", o.roi, "x,y,w,h in the (original) left image; default: whole image");
  cmd->add_option("--calib", o.calib, "calib.json: rectify the pair first");
  cmd->add_option("--shadow-fraction", o.shadow_fraction,
                  "prior shadow fraction p in [0, 1); 0 = none");
  cmd->add_flag("--fill", o.fill,
                "fill invalid pixels with the smaller nearest valid disparity on the row");
  cmd->add_option("--out", o.out, "output disparity, Middlebury PFM (invalid = inf)")->required();
  cmd->add_option("--confidence", o.confidence, "optional confidence image (PNG, 0 = invalid)");
  cmd->add_flag("--no-edges", no_edges, "skip the edge constraint (for comparisons only)");
  cmd->callback([&outcome] {
    o.edge_constraint = !no_edges;
    // Checked here, at the edge, so the message speaks of the options.
    if (o.disp_min > o.disp_max) {
      const std::string why = "--disp-min " + std::to_string(o.disp_min) + " is above --disp-max " +
                              std::to_string(o.disp_max) + ": the disparity range is empty";
      outcome.exit_code = fail("stereo", why.c_str());
      return;
    }
    if (std::abs(o.disp_min) > kMaxDisparityPx || std::abs(o.disp_max) > kMaxDisparityPx) {
      const std::string why =
          "--disp-min and --disp-max must lie within +-" + std::to_string(kMaxDisparityPx) + " px";
      outcome.exit_code = fail("stereo", why.c_str());
      return;
    }
    try {
      outcome.exit_code = run(o);
    } catch (const std::exception& e) {
      outcome.exit_code = fail("stereo", e.what());
    }
  });
}

}  // namespace petra::cli
