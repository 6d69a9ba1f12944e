// `petra eval --calib C --left L --right R --roi x,y,w,h --planes c
//             [--click u,v] [--method dp|gc] [--shadow-fraction p] --out DIR`:
// runs the onboard chain (algo/chain/pipeline) on a stereo pair as the rover would,
// writes planes.json, cloud.ply, mesh.ply, disparity.png and overlay.png into
// DIR (docs/icd.md), and prints a summary like the paper's Table 1 with the
// time of every step. Steps that run over a second report progress on stderr.
// --disparity D.pfm replays a given map instead of matching (to tell the
// matcher's errors from the reconstruction's).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "algo/camera/calib_json.hpp"
#include "algo/chain/pipeline.hpp"
#include "algo/propose/arm_reach.hpp"
#include "sim/cli/commands.hpp"
#include "sim/eval/eval_images.hpp"
#include "sim/eval/planes_json.hpp"
#include "sim/eval/ply_writer.hpp"
#include "sim/io/disparity_replay.hpp"
#include "sim/io/image_io.hpp"
#include "sim/io/parse_point.hpp"
#include "sim/io/parse_roi.hpp"
#include "sim/io/thread_cpu_clock.hpp"

namespace petra::cli {

namespace {

struct EvalOptions {
  std::string calib, left, right, roi, click, method = "dp", out, disparity, arm = "stowed";
  int planes = 0;
  std::size_t points = 0;  // 0: one per ROI pixel
  double shadow_fraction = PipelineParams{}.shadow_fraction;
};

// Reports a step on stderr once it has run for a second, then every second.
class Progress {
 public:
  Progress() : thread_([this] { watch(); }) {}
  ~Progress() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  static void on_step(void* self, PipelineStep s, bool running) {
    static_cast<Progress*>(self)->step(running ? step_name(s) : nullptr);
  }
  void step(const char* name) {
    std::lock_guard<std::mutex> lock(mutex_);
    current_ = name;
    started_ = std::chrono::steady_clock::now();
    reported_s_ = 0;
  }

 private:
  void watch() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!done_) {
      wake_.wait_for(lock, std::chrono::milliseconds(200));
      if (current_ == nullptr) continue;
      const double s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
      // At 1 s, then every 5 s.
      const int whole = static_cast<int>(s);
      if (whole >= 1 && (reported_s_ == 0 || whole >= reported_s_ + 5)) {
        reported_s_ = whole;
        std::fprintf(stderr, "petra eval: %s ... %d s\n", current_, reported_s_);
      }
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  const char* current_ = nullptr;
  std::chrono::steady_clock::time_point started_;
  int reported_s_ = 0;
  bool done_ = false;
  std::thread thread_;
};

// Rectified bounding box of the ROI outline (sizes the ground tool's budget).
Result<Rect> rectified_roi(const StereoRig& rig, const RectifiedPair& pair, const Rect& roi) {
  double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
  auto add = [&](double u, double v) -> Status {
    auto p = original_to_rectified(rig.left, pair.left, {u, v});
    if (!p) return p.error();
    x0 = std::min(x0, p->x());
    y0 = std::min(y0, p->y());
    x1 = std::max(x1, p->x());
    y1 = std::max(y1, p->y());
    return {};
  };
  for (int i = 0; i <= roi.w; ++i) {
    PETRA_TRY(add(roi.x + i - 0.5, roi.y - 0.5));
    PETRA_TRY(add(roi.x + i - 0.5, roi.y + roi.h - 0.5));
  }
  for (int j = 0; j <= roi.h; ++j) {
    PETRA_TRY(add(roi.x - 0.5, roi.y + j - 0.5));
    PETRA_TRY(add(roi.x + roi.w - 0.5, roi.y + j - 0.5));
  }
  return Rect{static_cast<int>(std::floor(x0)), static_cast<int>(std::floor(y0)),
              static_cast<int>(std::ceil(x1 - x0)) + 2, static_cast<int>(std::ceil(y1 - y0)) + 2};
}

double ms(std::uint64_t ns) {
  return static_cast<double>(ns) / 1e6;
}

// The calibration check in the operator's terms: a drifted pair says so.
void print_calibration(const CalibCheck& c) {
  if (!c.present) return;
  std::printf(
      "  calibration check      rows differ by %+.2f px (spread %.2f px, %d features): %s\n",
      c.vertical_offset_px, c.spread_px, c.features, to_string(c.verdict));
  if (c.verdict == CalibVerdict::drifted)
    std::printf("  the pair's rows differ by %.1f px: calibration has drifted\n",
                std::fabs(c.vertical_offset_px));
  else if (c.verdict == CalibVerdict::corrected)
    std::printf(
        "  the pair's rows differ by %.1f px: calibration has drifted; the right view was moved "
        "%s by %.2f rows before matching\n",
        std::fabs(c.vertical_offset_px), c.corrected_px > 0 ? "up" : "down",
        std::fabs(c.corrected_px));
  else if (c.verdict == CalibVerdict::unknown)
    std::printf("  too few features matched (%d) to check the calibration\n", c.features);
}

void print_summary(const EvalOptions& o, const PipelineOutput& out, double total_ms) {
  const ReconstructionOutput& r = out.result;
  const ReconstructionStats& s = r.stats;
  const Rect& q = out.roi_rectified;
  std::printf("petra eval: ROI %s (rectified %d,%d %dx%d), c = %d, method %s\n", o.roi.c_str(), q.x,
              q.y, q.w, q.h, o.planes, o.method.c_str());
  if (out.range.factor == 0) {
    std::printf("  disparity range        %.1f .. %.1f px   (given map, no matching)\n",
                s.disparity_min_px, s.disparity_max_px);
  } else {
    std::printf(
        "  disparity range        %.1f .. %.1f px   (search %d..%d px, coarse 1/%d: %ld matches)\n",
        s.disparity_min_px, s.disparity_max_px, out.range.min_px, out.range.max_px,
        out.range.factor, out.range.coarse_matches);
    print_calibration(out.calibration);
    if (out.method == MatchMethod::graph_cut) {
      const GraphCutReport& g = out.graph_cut;
      std::printf(
          "  shadow                 %ld px left, %ld left px touched by shadow   "
          "(threshold %d left, %d right)\n",
          out.shadow_left.shadow_pixels, g.shadow_pixels, out.shadow_left.threshold,
          out.shadow_right.threshold);
      std::printf(
          "  graph cut              %d cycles, %d expansions (%d skipped), energy %lld -> "
          "%lld, %ld matched, %ld occluded\n",
          g.cycles, g.expansions, g.expansions_skipped, static_cast<long long>(g.energy_start),
          static_cast<long long>(g.energy), g.matched_pixels, g.occluded_pixels);
    } else {
      std::printf("  shadow                 %ld + %ld px   (threshold %d left, %d right)\n",
                  out.shadow_left.shadow_pixels, out.match.rejected_shadow_right,
                  out.shadow_left.threshold, out.shadow_right.threshold);
    }
  }
  std::printf("  dense points           %ld of %ld ROI px   (before the mean filter)\n",
              s.dense_points, static_cast<long>(q.w) * q.h);
  std::printf("  filtered points        %ld\n", s.filtered_points);
  std::printf(
      "  3-D points, triangles  %zu (pixel stride %d), %zu kept of %zu   (removed: %zu long, "
      "%zu oblique)\n",
      s.triangulated, s.point_stride, s.mesh.kept, s.delaunay_triangles, s.mesh.removed_long,
      s.mesh.removed_grazing);
  const Eigen::Vector3d& gn = r.ground.plane.normal;
  std::printf("  ground plane           n (%.4f, %.4f, %.4f), d %.2f mm, RMS %.2f mm, %zu points\n",
              gn.x(), gn.y(), gn.z(), r.ground.plane.d, r.ground.rms_mm, r.ground.ground_points);
  std::printf("  rock                   %zu points, %zu triangles\n", r.ground.rock_points,
              s.rock_triangles);
  if (r.click_region.loosened > 0)
    std::printf(
        "  click region           grown again with the concave limit x %d: the first growth "
        "held under %.0f %% of the ROI's points (a groove under the click)\n",
        1 << r.click_region.loosened, 100 * PipelineParams{}.reconstruction.click_region.min_share);
  if (r.support_planes > 0)
    std::printf(
        "  support                %d plane(s) on the surface the rock stands on: %zu points "
        "dropped from the rock, planes found again\n",
        r.support_planes, r.support_points);
  std::printf("  grind planes found     %d of %d   (%d of them refined on the gray levels)\n",
              r.planes.accepted, o.planes, out.planes_refined);
  if (out.footprints_again > 0)
    std::printf(
        "  footprints again       %d plane(s): the arm no longer reached the disc along the "
        "refined normal; the flat discs asked again\n",
        out.footprints_again);
  for (int k = 0; k < r.planes.accepted; ++k) {
    const GrindPlane& p = r.planes.planes[k];
    std::printf(
        "    %d  normal (%.4f, %.4f, %.4f)  centroid (%.1f, %.1f, %.1f) mm  area %.0f mm2  RMS "
        "%.2f mm  "
        "%zu triangles  seen at %.0f deg\n",
        k + 1, p.normal.x(), p.normal.y(), p.normal.z(), p.centroid_mm.x(), p.centroid_mm.y(),
        p.centroid_mm.z(), p.area_mm2, p.rms_mm, p.triangles, p.view_angle_deg);
    std::printf(
        "       footprint %.0f mm: RMS %.2f mm, peak-to-valley %.2f mm (%s plane); 1-sigma %.2f "
        "deg, %.2f mm\n",
        r.planes.footprint_diameter_mm, p.footprint_rms_mm, p.footprint_pv_mm,
        p.footprint_local ? "the disc's own" : "the face's", p.normal_sigma_deg, p.offset_sigma_mm);
  }
  if (r.planes.accepted < o.planes) {
    if (r.planes.classes < o.planes)
      std::printf("    only %d distinct face orientations (more than %.0f deg apart) on the rock\n",
                  r.planes.classes, PipelineParams{}.reconstruction.grind.angle.min_separation_deg);
    for (int k = r.planes.accepted; k < r.planes.count; ++k) {
      const GrindPlane& p = r.planes.planes[k];
      std::printf(
          "    not used: normal (%.3f, %.3f, %.3f), area %.0f mm2, RMS %.2f mm, footprint RMS "
          "%.2f mm, 1-sigma %.2f deg %.2f mm: %s\n",
          p.normal.x(), p.normal.y(), p.normal.z(), p.area_mm2, p.rms_mm, p.footprint_rms_mm,
          p.normal_sigma_deg, p.offset_sigma_mm, verdict_name(p.verdict));
    }
  }
  std::printf("  timings (CPU ms):");
  for (std::size_t i = 0; i < out.timings.count; ++i)
    std::printf("%s %s %.1f", i == 0 ? "" : " |", out.timings.steps[i].name,
                ms(out.timings.steps[i].ns));
  std::printf("\n  total %.1f CPU ms onboard chain; %.0f ms wall with file I/O\n",
              ms(out.timings.total_ns()), total_ms);
}

int run(const EvalOptions& o) {
  namespace fs = std::filesystem;
  const auto t0 = std::chrono::steady_clock::now();
  PipelineRequest req;
  if (o.method == "gc") {
    req.method = MatchMethod::graph_cut;
  } else if (o.method != "dp") {
    return fail("eval", ("--method " + o.method + ": expected dp or gc").c_str());
  }
  if (o.planes < 1 || o.planes > kMaxClasses)
    return fail("eval", ("--planes " + std::to_string(o.planes) + ": c must be 1.." +
                         std::to_string(kMaxClasses))
                            .c_str());
  if (o.arm != "stowed" && o.arm != "none")
    return fail("eval", ("--arm " + o.arm + ": expected stowed or none").c_str());
  // As EVALUATE on board with the rover's arm stowed: footprints the arm reaches.
  const arm::JointLimits limits = arm::default_joint_limits();
  const arm::ArmGeometry arm_geometry = arm::rover_arm_geometry();
  const ArmReach reach(arm_geometry, limits, arm::stow_pose(), arm::kDefaultStandoffMm);
  if (o.arm == "stowed") req.reach = &reach;
  auto roi = io::parse_roi(o.roi);
  if (!roi) return fail("eval", roi.error().message);
  req.roi = *roi;
  req.planes = o.planes;
  if (!o.click.empty()) {
    auto c = io::parse_point(o.click);
    if (!c) return fail("eval", c.error().message);
    req.has_click = true;
    req.click_u = c->u;
    req.click_v = c->v;
  }
  auto text = io::read_text_file(o.calib);
  if (!text) return fail("eval", text.error().message);
  auto rig = parse_calib_json(*text);
  if (!rig) return fail("eval", rig.error().message);
  auto left = io::read_gray_image(o.left);
  if (!left) return fail("eval", left.error().message);
  auto right = io::read_gray_image(o.right);
  if (!right) return fail("eval", right.error().message);
  if (left->width != rig->left.width || left->height != rig->left.height ||
      right->width != left->width || right->height != left->height) {
    char msg[200];
    std::snprintf(msg, sizeof msg, "images are %dx%d and %dx%d, calibration is for %dx%d",
                  left->width, left->height, right->width, right->height, rig->left.width,
                  rig->left.height);
    return fail("eval", msg);
  }
  if (!req.roi.inside(left->width, left->height)) {
    char msg[160];
    std::snprintf(msg, sizeof msg, "ROI %d,%d %dx%d is not inside the %dx%d image", req.roi.x,
                  req.roi.y, req.roi.w, req.roi.h, left->width, left->height);
    return fail("eval", msg);
  }

  // The ground tool sizes the budget for the problem it is given.
  PipelineParams params;
  params.shadow_fraction = o.shadow_fraction;
  auto geometry = rectify_geometry(*rig, rig->left.width, rig->left.height);
  if (!geometry) return fail("eval", geometry.error().message);
  auto rroi = rectified_roi(*rig, *geometry, req.roi);
  if (!rroi) return fail("eval", rroi.error().message);
  PipelineBudget budget;
  budget.image_width = left->width;
  budget.image_height = left->height;
  budget.max_roi_width = std::clamp(rroi->w, 16, left->width);
  budget.max_roi_height = std::clamp(rroi->h, 16, left->height);
  budget.max_disparities = params.range.search_max_px - params.range.search_min_px + 1;
  budget.graph_cut = req.method == MatchMethod::graph_cut;
  // One point per ROI pixel unless asked (--points: e.g. the flight budget's).
  budget.max_points = o.points > 0 ? o.points
                                   : static_cast<std::size_t>(budget.max_roi_width) *
                                         static_cast<std::size_t>(budget.max_roi_height);
  const Status valid = validate(params);
  if (!valid.ok()) return fail("eval", valid.error().message);
  std::vector<std::byte> block(Pipeline::arena_bytes(budget, params));
  Arena arena(block);
  Progress progress;
  progress.step("rectification tables");
  auto pipeline = Pipeline::create(*rig, budget, params, arena);
  progress.step(nullptr);
  if (!pipeline) return fail("eval", pipeline.error().message);
  StepClock clock{sim::thread_cpu_ns, &progress, &Progress::on_step};
  std::vector<std::int16_t> given;  // --disparity: the map replayed instead of matching
  Result<PipelineOutput> out = Error::make(Errc::not_ready, "not run");
  if (o.disparity.empty()) {
    out = pipeline->run(left->view(), right->view(), req, clock);
  } else {
    auto read = io::read_disparity_q4(o.disparity, left->width, left->height);
    if (!read) return fail("eval", read.error().message);
    given = std::move(*read);
    auto droi = pipeline->rectifier().roi_to_rectified(StereoSide::left, req.roi);
    if (!droi) return fail("eval", droi.error().message);
    const ImageView<const std::int16_t> whole(given.data(), left->width, left->height);
    const ConstDisparityMap map(whole.sub(*droi), *droi);
    out = pipeline->run_with_disparity(left->view(), map, req, clock);
  }
  if (!out) {
    print_calibration(pipeline->last_calibration());  // a drifted pair may be why
    return fail("eval", out.error().message);
  }

  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (ec) return fail("eval", ("cannot create " + o.out + ": " + ec.message()).c_str());
  const std::string dir = o.out + "/";
  // The matcher's gray-level map when it matched this pair (not on a replayed map).
  const bool gc = out->method == MatchMethod::graph_cut;
  const eval::GrayMapQ8 gray{gc ? out->graph_cut.gray_gain_q8 : out->match.gray_gain_q8,
                             gc ? out->graph_cut.gray_offset_q8 : out->match.gray_offset_q8};
  Status s = io::write_text_file(
      dir + "planes.json", eval::format_planes_json(out->result, &out->calibration,
                                                    out->calibration.present ? &gray : nullptr));
  if (s.ok()) s = eval::write_ply(dir + "cloud.ply", out->result, out->left_rectified, false);
  if (s.ok()) s = eval::write_ply(dir + "mesh.ply", out->result, out->left_rectified, true);
  if (s.ok()) s = io::write_png(dir + "disparity.png", eval::disparity_picture(out->disparity));
  if (s.ok())
    s = io::write_png(dir + "overlay.png",
                      eval::overlay_picture(*out, pipeline->rectifier().geometry()));
  if (!s.ok()) return fail("eval", s.error().message);
  const double total =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  print_summary(o, *out, total);
  return 0;
}

}  // namespace

void add_eval(CLI::App& app, Outcome& outcome) {
  auto* cmd = app.add_subcommand(
      "eval", "Run the onboard chain on a stereo pair: grind planes and products");
  static EvalOptions o;
  cmd->add_option("--calib", o.calib, "calib.json (Tsai RAC, mm)")->required();
  cmd->add_option("--left", o.left, "left image (PGM, PPM or PNG)")->required();
  cmd->add_option("--right", o.right, "right image")->required();
  cmd->add_option("--roi", o.roi, "x,y,w,h in the left image")->required();
  cmd->add_option("--planes", o.planes, "c: flat faces to find (1..8, usually 2 or 3)")->required();
  cmd->add_option("--click", o.click, "u,v: a point on the rock in the left image");
  cmd->add_option("--method", o.method, "matcher: dp (scanline DP, default) or gc (graph cut)");
  cmd->add_option("--shadow-fraction", o.shadow_fraction,
                  "expected shadow share of the ROI, [0, 1)");
  cmd->add_option(
      "--disparity", o.disparity,
      "replay this rectified left-view PFM instead of matching (e.g. disparity_truth.pfm)");
  cmd->add_option("--points", o.points,
                  "3-D points budget (default: one per ROI pixel; petra-fsw's: its boot line); "
                  "more valid disparities are taken on a pixel stride");
  cmd->add_option("--arm", o.arm,
                  "stowed (default: footprints the rover's arm reaches from its stowed pose, as "
                  "EVALUATE on board) or none (the most level footprint, reached or not)");
  cmd->add_option("--out", o.out, "output directory")->required();
  cmd->callback([&outcome] {
    try {
      outcome.exit_code = run(o);
    } catch (const std::exception& e) {
      outcome.exit_code = fail("eval", e.what());
    }
  });
}

}  // namespace petra::cli
