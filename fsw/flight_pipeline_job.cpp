#include "fsw/flight_pipeline_job.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <utility>

#include "algo/chain/products.hpp"
#include "cmd/param_defs.hpp"
#include "fsw/memory_table.hpp"
#include "fsw/step_slots.hpp"

namespace petra::fsw {

namespace {

// Largest ROI the flight job takes (rectified px): the paper's 640 x 480
// window; the smallest it shrinks to for a small arena.
constexpr int kMaxRoiWidth = 640;
constexpr int kMinRoiWidth = 64;
// The flight default: the largest ROI the operator may select (original px).
constexpr int kDefaultRoiWidth = 512;
constexpr int kDefaultRoiHeight = 384;
// The graph cut in bands of 128 rows (+ 16 above and below): about 200 B per
// pixel of a 160-row band instead of the whole ROI (docs/graphcut.md "Bands").
constexpr int kGraphCutBandRows = 128;
constexpr int kGraphCutBandOverlap = 16;
constexpr std::size_t kSlack = 4 * 64;

// The StepClock's context: the injected clock for the step times, the step in
// progress (so a failure names where it happened), and the executive's cancel
// flag for the pipeline's step boundaries.
struct StepTracker {
  const hal::Clock* clock = nullptr;
  Step current = Step::RECTIFY;
  const std::atomic<bool>* cancel = nullptr;
  static std::uint64_t now_ns(void* self) {
    return static_cast<std::uint64_t>(static_cast<StepTracker*>(self)->clock->monotonic_ns());
  }
  static void on_step(void* self, PipelineStep step, bool running) {
    if (running) static_cast<StepTracker*>(self)->current = slot_of(step);
  }
  static bool cancel_requested(void* self) {
    const auto* t = static_cast<StepTracker*>(self);
    return t->cancel != nullptr && t->cancel->load(std::memory_order_relaxed);
  }
};

std::uint32_t to_us(std::uint64_t ns) {
  return static_cast<std::uint32_t>(std::min<std::uint64_t>(ns / 1000, 0xFFFFFFFFull));
}

std::size_t product_bytes(int roi_w, int roi_h, std::size_t cloud_points) {
  const auto px = static_cast<std::size_t>(roi_w) * static_cast<std::size_t>(roi_h);
  return px + 3 * px + 3 * sizeof(float) * cloud_points + kSlack;
}

// The one conversion of a plane, at the algo/fsw boundary: algo does not
// know telemetry, and from here on the plane stays this packet (the
// executive's downlink and the arm target read it). Identity fields
// (eval_id, rank, plane_count) are stamped at publishing.
tlm::GrindPlane plane_packet(const GrindPlane& g, double footprint_diameter_mm) {
  tlm::GrindPlane p;
  p.normal = {g.normal.x(), g.normal.y(), g.normal.z()};
  p.centroid_mm = {g.centroid_mm.x(), g.centroid_mm.y(), g.centroid_mm.z()};
  p.area_mm2 = g.area_mm2;
  p.flatness_rms_mm = g.rms_mm;
  p.triangles = static_cast<std::uint32_t>(g.triangles);
  p.verdict = static_cast<std::uint8_t>(g.verdict);
  p.plane_source = g.footprint_local ? 1 : 0;
  p.normal_sigma_deg = static_cast<float>(g.normal_sigma_deg);
  p.offset_sigma_mm = static_cast<float>(g.offset_sigma_mm);
  p.footprint_rms_mm = static_cast<float>(g.footprint_rms_mm);
  p.footprint_diameter_mm = static_cast<float>(footprint_diameter_mm);
  p.footprint_reach = static_cast<std::uint8_t>(g.footprint_reach);
  return p;
}

// The pictures: algo/chain/products (the one palette, the drawing `petra eval` shares).
Status make_products(const PipelineOutput& p, const RectifiedPair& pair, std::size_t max_cloud,
                     Arena& arena, EvalOutput& out) {
  const Rect roi = p.disparity.roi;
  const int w = roi.w, h = roi.h;
  const auto px = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);

  auto gray = arena.allocate<std::uint8_t>(px, "disparity product");
  if (!gray) return gray.error();
  PETRA_TRY(products::disparity_gray(p.disparity, Gray8View(gray->data(), w, h)));
  out.disparity_gray = ConstGray8View(gray->data(), w, h);

  auto rgb = arena.allocate<std::uint8_t>(3 * px, "overlay product");
  if (!rgb) return rgb.error();
  PETRA_TRY(products::overlay(p, pair, ImageView<std::uint8_t>(rgb->data(), 3 * w, h)));
  out.overlay_rgb = ImageView<const std::uint8_t>(rgb->data(), 3 * w, h);
  const ReconstructionOutput& r = p.result;

  // Cloud: at most the product's capacity, a regular stride through the points.
  const std::size_t points = r.xyz_mm.size();
  const std::size_t keep = std::min(points, max_cloud);
  if (keep > 0) {
    auto xyz = arena.allocate<float>(3 * keep, "cloud product");
    if (!xyz) return xyz.error();
    for (std::size_t i = 0; i < keep; ++i) {
      const Eigen::Vector3d& q = r.xyz_mm[i * points / keep];
      for (int c = 0; c < 3; ++c)
        (*xyz)[3 * i + static_cast<std::size_t>(c)] = static_cast<float>(q[c]);
    }
    out.cloud_xyz_mm = std::span<const float>(xyz->data(), 3 * keep);
  }
  return {};
}

}  // namespace

namespace {

// The largest rectified ROI any w x h ROI of the original left image maps to,
// over positions on a grid (1 px of slack for the steps between them). Without
// a rig, w x h (runs then fail not_ready anyway).
std::pair<int, int> rectified_bound(const StereoRig* rig, int image_w, int image_h, int w, int h) {
  if (rig == nullptr) return {w, h};
  auto geometry = rectify_geometry(*rig, rig->left.width, rig->left.height);
  if (!geometry) return {image_w, image_h};
  const int W = rig->left.width, H = rig->left.height;
  w = std::min(w, W);
  h = std::min(h, H);
  int bw = 0, bh = 0;
  const int step = std::max(16, std::min(w, h) / 8);
  for (int y = 0;; y = std::min(y + step, H - h)) {
    for (int x = 0;; x = std::min(x + step, W - w)) {
      auto r = roi_to_rectified(rig->left, geometry->left, Rect{x, y, w, h}, W, H);
      if (r) {
        bw = std::max(bw, r->w);
        bh = std::max(bh, r->h);
      }
      if (x == W - w) break;
    }
    if (y == H - h) break;
  }
  return {std::min(bw + 1, W), std::min(bh + 1, H)};
}

petra::PipelineBudget roi_budget(const JobBudget& budget, int roi_w, int roi_h) {
  const int image_w = budget.rig != nullptr ? budget.rig->left.width : budget.max_width;
  const int image_h = budget.rig != nullptr ? budget.rig->left.height : budget.max_height;
  petra::PipelineBudget b;
  b.image_width = image_w;
  b.image_height = image_h;
  const auto [w, h] = rectified_bound(budget.rig, image_w, image_h, roi_w, roi_h);
  b.max_roi_width = std::min(w, image_w);
  b.max_roi_height = std::min(h, image_h);
  b.graph_cut = true;  // room in the matching step: MATCH_METHOD 1 needs no new memory
  b.graph_cut_bands = {kGraphCutBandRows, kGraphCutBandOverlap};
  const petra::PipelineParams p =
      FlightPipelineJob::pipeline_params(FlightPipelineJob::default_settings());
  b.max_disparities = p.range.search_max_px - p.range.search_min_px + 1;
  return b;
}

}  // namespace

std::size_t FlightPipelineJob::need_bytes(const petra::PipelineBudget& b,
                                          std::size_t cloud_points) {
  return Pipeline::arena_bytes(b, pipeline_params(default_settings())) +
         product_bytes(b.max_roi_width, b.max_roi_height, cloud_points);
}

FlightPipelineJob::Sizing FlightPipelineJob::sizing(const JobBudget& budget) {
  auto make = [&](int w, int h) {
    w = std::min(w, budget.max_width);
    h = std::min(h, budget.max_height);
    return Sizing{roi_budget(budget, w, h), w, h};
  };
  if (budget.max_roi_width > 0 && budget.max_roi_height > 0)
    return make(budget.max_roi_width, budget.max_roi_height);
  if (budget.arena_limit == 0) return make(kDefaultRoiWidth, kDefaultRoiHeight);
  // An arena given without an ROI: the largest 4:3 ROI that fits it.
  for (int w = kMaxRoiWidth; w > kMinRoiWidth; w -= 16) {
    const Sizing s = make(w, w * 3 / 4);
    if (need_bytes(s.pipeline, budget.max_cloud_points) <= budget.arena_limit) return s;
  }
  return make(kMinRoiWidth, kMinRoiWidth * 3 / 4);
}

petra::PipelineBudget FlightPipelineJob::pipeline_budget(const JobBudget& budget) {
  return sizing(budget).pipeline;
}

// The parameter table's defaults: the pipeline is built for them at init, so
// the first EVALUATE with default parameters rebuilds nothing.
FlightPipelineJob::Settings FlightPipelineJob::default_settings() {
  return {param_default(ParamId::SHADOW_FRACTION),
          static_cast<int>(param_default(ParamId::DISP_MIN_PX)),
          static_cast<int>(param_default(ParamId::DISP_MAX_PX))};
}

petra::PipelineParams FlightPipelineJob::pipeline_params(const Settings& settings) {
  petra::PipelineParams p;
  p.shadow_fraction = settings.shadow_fraction;
  p.range.search_min_px = settings.disp_min_px;
  p.range.search_max_px = settings.disp_max_px;
  return p;
}

ProposerBudget FlightPipelineJob::proposer_budget(const Sizing& s) {
  ProposerBudget b;
  b.pipeline = s.pipeline;
  b.max_roi_width = s.roi_width;
  b.max_roi_height = s.roi_height;
  return b;
}

// The tables, then the larger of an evaluation's run with its products and
// the proposer's (a chain run or its detection): one run at a time.
std::size_t FlightPipelineJob::arena_bytes(const JobBudget& budget) const {
  const Sizing s = sizing(budget);
  return std::max(need_bytes(s.pipeline, budget.max_cloud_points),
                  Proposer::arena_bytes(proposer_budget(s), pipeline_params(default_settings())));
}

JobLimits FlightPipelineJob::limits() const {
  return {roi_width_, roi_height_, budget_.max_disparities};
}

int FlightPipelineJob::describe_memory(char* buf, std::size_t size) const {
  if (rig_ == nullptr) return std::snprintf(buf, size, "no calib.json: no pipeline memory\n");
  const int n = format_memory_header(buf, size);
  const std::size_t at = std::min(static_cast<std::size_t>(n), size);
  return n + format_memory_row(buf + at, size - at, roi_width_, roi_height_, budget_,
                               max_cloud_points_);
}

Status FlightPipelineJob::init(const JobBudget& budget, const StereoRig* rig, Arena& arena) {
  rig_ = rig;
  arena_ = &arena;
  arm_geometry_ = budget.arm_geometry;
  max_cloud_points_ = budget.max_cloud_points;
  ready_ = false;
  proposer_fits_ = false;
  if (rig == nullptr) return {};  // runs fail not_ready: no calib.json configured
  if (rig->left.width > budget.max_width || rig->left.height > budget.max_height)
    return Error::make(Errc::capacity_exceeded,
                       "calib.json is for %dx%d images, budget.image_width/height is %dx%d",
                       rig->left.width, rig->left.height, budget.max_width, budget.max_height);
  // The ROI sized for the budget, the image for the rig (smaller or equal: less memory).
  JobBudget sized = budget;
  sized.rig = rig;
  const Sizing s = sizing(sized);
  budget_ = s.pipeline;
  roi_width_ = s.roi_width;
  roi_height_ = s.roi_height;
  const ProposerBudget pb = proposer_budget(s);
  const bool fits =
      arena.remaining() >= Proposer::arena_bytes(pb, pipeline_params(default_settings()));
  settings_ = default_settings();
  auto p = Pipeline::create(*rig_, budget_, pipeline_params(settings_), arena);
  if (!p) return p.error();
  ++table_builds_;
  pipeline_ = *p;
  ready_ = true;
  if (!fits) return {};  // PROPOSE fails capacity_exceeded; can_propose() says so
  auto q = Proposer::create(pipeline_, pb, arm_geometry_, arm_limits_, arena);
  if (!q) return q.error();
  proposer_ = *q;
  proposer_fits_ = true;
  return {};
}

// The pipeline's parameters for the next run: the tables stay.
Status FlightPipelineJob::configure(const Settings& settings) {
  if (settings.disp_min_px < 0 || settings.disp_min_px >= settings.disp_max_px)
    return Error::make(Errc::invalid_argument, "DISP_MIN_PX %d .. DISP_MAX_PX %d: not an envelope",
                       settings.disp_min_px, settings.disp_max_px);
  if (settings.disp_max_px - settings.disp_min_px + 1 > budget_.max_disparities)
    return Error::make(Errc::capacity_exceeded,
                       "DISP_MIN_PX %d .. DISP_MAX_PX %d: wider than the budget's %d disparities",
                       settings.disp_min_px, settings.disp_max_px, budget_.max_disparities);
  PETRA_TRY(pipeline_.set_params(pipeline_params(settings)));
  settings_ = settings;
  return {};
}

Status FlightPipelineJob::run(const EvalRequest& request, Arena& arena,
                              const std::atomic<bool>& cancel, EvalOutput& out) {
  out.failed_step = Step::RECTIFY;
  if (rig_ == nullptr)
    return Error::make(Errc::not_ready, "no calib.json configured: the pipeline needs the rig");
  if (&arena != arena_)
    return Error::make(Errc::invalid_argument, "run: not the arena given to init");
  const MatchMethod method = request.selection.method;
  if (method != MatchMethod::dp && method != MatchMethod::graph_cut)
    return Error::make(Errc::invalid_argument, "MATCH_METHOD %d: 0 (dp) or 1 (graph cut)",
                       static_cast<int>(method));
  if (request.left.empty() || request.right.empty())
    return Error::make(Errc::invalid_argument, "run: no stereo pair");
  if (cancel.load(std::memory_order_relaxed))
    return Error::make(Errc::cancelled, "evaluation cancelled");

  StepTracker tracker{clock_, Step::RECTIFY, &cancel};
  const StepClock clock{&StepTracker::now_ns, &tracker, &StepTracker::on_step,
                        &StepTracker::cancel_requested};
  if (request.kind == JobKind::PROPOSE) {
    const Status s = propose(request, clock, out);
    if (!s) out.failed_step = tracker.current;
    return s;
  }
  if (!ready_) return Error::make(Errc::not_ready, "the pipeline was not built at init");
  const Settings wanted{request.shadow_fraction, request.disp_min_px, request.disp_max_px};
  if (!(wanted == settings_)) PETRA_TRY(configure(wanted));
  const ArmReach reach(arm_geometry_, arm_limits_, request.arm_pose,
                       ::petra::arm::kDefaultStandoffMm);
  PipelineRequest selection = request.selection;
  selection.reach = &reach;
  auto result = pipeline_.run(request.left, request.right, selection, clock);
  if (!result) {
    out.failed_step = tracker.current;
    return result.error();
  }
  if (cancel.load(std::memory_order_relaxed))
    return Error::make(Errc::cancelled, "evaluation cancelled");
  const PipelineOutput& p = *result;
  for (std::size_t i = 0; i < p.timings.count; ++i)
    out.step_us[static_cast<std::size_t>(slot_of(p.timings.steps[i].step))] +=
        to_us(p.timings.steps[i].ns);

  const ReconstructionOutput& r = p.result;
  for (int k = 0; k < r.planes.accepted; ++k) {
    const GrindPlane& g = r.planes.planes[k];
    if (g.area_mm2 < request.min_plane_area_mm2) continue;  // ranked by area: the rest are smaller
    if (!out.planes.push_back(plane_packet(g, r.planes.footprint_diameter_mm))) break;
  }
  for (int k = r.planes.accepted; k < r.planes.count; ++k)  // refused ones follow, largest first
    if (r.planes.planes[k].verdict != PlaneVerdict::surplus) {
      out.refused_verdict = static_cast<std::uint8_t>(r.planes.planes[k].verdict);
      break;
    }
  const Eigen::Vector3d& gn = r.ground.plane.normal;
  out.ground_normal = {gn.x(), gn.y(), gn.z()};
  out.ground_d_mm = r.ground.plane.d;
  out.ground_points = static_cast<std::uint32_t>(r.ground.ground_points);
  out.segmentation = static_cast<std::uint8_t>(r.segmentation);
  out.calib_vertical_offset_px = static_cast<float>(p.calibration.vertical_offset_px);
  out.calib_spread_px = static_cast<float>(p.calibration.spread_px);
  out.calib_features = static_cast<std::uint16_t>(p.calibration.features);
  out.calib_verdict = static_cast<std::uint8_t>(p.calibration.verdict);
  // The gray-level map of the matcher that ran (1/256 gain, 1/256 level).
  const bool gc = p.method == MatchMethod::graph_cut;
  const int gain_q8 = gc ? p.graph_cut.gray_gain_q8 : p.match.gray_gain_q8;
  const int offset_q8 = gc ? p.graph_cut.gray_offset_q8 : p.match.gray_offset_q8;
  out.gray_gain = static_cast<float>(gain_q8 / 256.0);
  out.gray_offset = static_cast<float>(offset_q8 / 256.0);
  out.click_loosened = static_cast<std::uint8_t>(r.click_region.loosened);
  out.dense_points = static_cast<std::uint32_t>(r.stats.dense_points);
  out.filtered_points = static_cast<std::uint32_t>(r.stats.filtered_points);
  out.disparity_min = static_cast<float>(r.stats.disparity_min_px);
  out.disparity_max = static_cast<float>(r.stats.disparity_max_px);

  out.failed_step = Step::PRODUCTS;
  const std::int64_t t0 = clock_->monotonic_ns();
  PETRA_TRY(make_products(p, pipeline_.rectifier().geometry(), max_cloud_points_, arena, out));
  out.step_us[static_cast<std::size_t>(Step::PRODUCTS)] =
      to_us(static_cast<std::uint64_t>(clock_->monotonic_ns() - t0));
  return {};
}

Status FlightPipelineJob::propose(const EvalRequest& request, const StepClock& clock,
                                  EvalOutput& out) {
  if (!proposer_fits_)
    return Error::make(Errc::capacity_exceeded, "proposer: the arena is smaller than it needs");
  const Settings wanted{request.shadow_fraction, request.disp_min_px, request.disp_max_px};
  if (!(wanted == settings_)) PETRA_TRY(configure(wanted));
  auto list = proposer_.run(request.left, request.right, request.proposal, request.arm_pose, clock);
  if (!list) return list.error();
  out.proposals = *list;
  return {};
}

}  // namespace petra::fsw
