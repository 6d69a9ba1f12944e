#include "algo/chain/pipeline.hpp"

#include <algorithm>
#include <cmath>

#include "algo/mesh/delaunay.hpp"

namespace petra {

namespace {

constexpr std::size_t kSlack = 64 * 16;  // alignment padding of the run's allocations

ReconstructionBudget recon_budget(const PipelineBudget& b) {
  return ReconstructionBudget{b.max_roi_width, b.max_roi_height, points_of(b)};
}

GraphCutBudget graph_cut_budget(const PipelineBudget& b) {
  return GraphCutBudget{b.max_roi_width, b.max_roi_height, b.max_disparities};
}

std::size_t image_bytes(const PipelineBudget& b) {
  return static_cast<std::size_t>(b.image_width) * static_cast<std::size_t>(b.image_height);
}

}  // namespace

std::size_t points_of(const PipelineBudget& b) {
  return b.max_points > 0 ? b.max_points
                          : static_cast<std::size_t>((b.max_roi_width + 1) / 2) *
                                static_cast<std::size_t>((b.max_roi_height + 1) / 2);
}

Status validate(const PipelineBudget& b) {
  if (b.image_width < 16 || b.image_width > kRemapMaxSide || b.image_height < 16 ||
      b.image_height > kRemapMaxSide)
    return Error::make(Errc::invalid_argument, "budget: image %dx%d not within 16..%d",
                       b.image_width, b.image_height, kRemapMaxSide);
  if (b.max_roi_width < 16 || b.max_roi_width > b.image_width || b.max_roi_height < 16 ||
      b.max_roi_height > b.image_height)
    return Error::make(Errc::invalid_argument, "budget: max ROI %dx%d not within 16 px..the image",
                       b.max_roi_width, b.max_roi_height);
  if (b.max_disparities < 8 || b.max_disparities > 512)
    return Error::make(Errc::invalid_argument, "budget: max_disparities %d not within 8..512",
                       b.max_disparities);
  return validate(recon_budget(b));
}

Status validate(const PipelineParams& p) {
  if (!(p.shadow_fraction >= 0.0 && p.shadow_fraction < 1.0))
    return Error::make(Errc::invalid_argument, "pipeline: shadow_fraction %.3g not in [0, 1)",
                       p.shadow_fraction);
  PETRA_TRY(validate(p.range));
  PETRA_TRY(validate(p.calib_check));
  PETRA_TRY(validate(p.subpixel));
  PETRA_TRY(validate(p.photometric));
  PETRA_TRY(validate(p.reconstruction.filter));
  PETRA_TRY(validate(p.reconstruction.normals));
  PETRA_TRY(validate(p.reconstruction.mesh));
  PETRA_TRY(validate(p.reconstruction.ground));
  PETRA_TRY(validate(p.reconstruction.grind));
  return {};
}

std::size_t PipelineMemory::largest_step() const {
  return std::max({range, calib_check, match_dp, match_graph_cut, reconstruction + refinement});
}

std::size_t PipelineMemory::run() const {
  return rectified + masks_disparity + largest_step() + slack;
}

PipelineMemory Pipeline::memory(const PipelineBudget& b, const PipelineParams& p) {
  const std::size_t roi =
      static_cast<std::size_t>(b.max_roi_width) * static_cast<std::size_t>(b.max_roi_height);
  const std::size_t right_area = static_cast<std::size_t>(b.max_roi_width + b.max_disparities) *
                                 static_cast<std::size_t>(b.max_roi_height);
  PipelineMemory m;
  m.tables = 2 * Rectifier::table_entries(b.image_width, b.image_height) * sizeof(RemapEntry) + 64;
  m.rectified = 2 * image_bytes(b);
  m.masks_disparity = roi + right_area + roi * sizeof(std::int16_t);
  m.range = disparity_range_scratch_bytes(b.image_width, b.image_height, b.max_roi_width,
                                          b.max_roi_height, p.range);
  m.match_dp =
      match_dp_scratch_bytes(MatchBudget{b.max_roi_width, b.max_roi_height, b.max_disparities});
  m.match_graph_cut =
      b.graph_cut ? graph_cut_bands_bytes(graph_cut_budget(b), b.graph_cut_bands) : 0;
  m.reconstruction = reconstruction_arena_bytes(recon_budget(b));
  m.refinement =
      std::max(grind_photometric_scratch_bytes(b.max_roi_width, b.max_roi_height),
               footprint_again_scratch_bytes(delaunay_max_triangles(recon_budget(b).max_points)));
  m.calib_check = calib_check_scratch_bytes(p.calib_check);
  m.slack = kSlack;
  return m;
}

std::size_t Pipeline::init_bytes(const PipelineBudget& b) {
  return memory(b, PipelineParams{}).tables;
}

std::size_t Pipeline::run_bytes(const PipelineBudget& b, const PipelineParams& p) {
  return memory(b, p).run();
}

Result<Pipeline> Pipeline::create(const StereoRig& rig, const PipelineBudget& budget,
                                  const PipelineParams& params, Arena& arena) {
  PETRA_TRY(validate(budget));
  PETRA_TRY(validate(params));
  if (rig.left.width != budget.image_width || rig.left.height != budget.image_height)
    return Error::make(Errc::invalid_argument,
                       "pipeline: calibration is for %dx%d, budget for %dx%d", rig.left.width,
                       rig.left.height, budget.image_width, budget.image_height);
  if (arena.remaining() < arena_bytes(budget, params))
    return Error::make(Errc::capacity_exceeded,
                       "pipeline: arena holds %zu bytes, the budget needs %zu", arena.remaining(),
                       arena_bytes(budget, params));
  const std::size_t entries = Rectifier::table_entries(budget.image_width, budget.image_height);
  auto tl = arena.allocate<RemapEntry>(entries, "left remap table");
  if (!tl) return tl.error();
  auto tr = arena.allocate<RemapEntry>(entries, "right remap table");
  if (!tr) return tr.error();
  auto rect = Rectifier::create(rig, *tl, *tr);
  if (!rect) return rect.error();
  Pipeline p;
  p.arena_ = &arena;
  p.run_mark_ = arena.mark();
  p.rectifier_ = *rect;
  p.budget_ = budget;
  p.params_ = params;
  p.max_points_ = points_of(budget);
  return p;
}

Status Pipeline::set_params(const PipelineParams& params) {
  if (arena_ == nullptr) return Error::make(Errc::not_ready, "pipeline: not created");
  PETRA_TRY(validate(params));
  const std::size_t room = arena_->capacity() - run_mark_;
  if (room < run_bytes(budget_, params))
    return Error::make(Errc::capacity_exceeded,
                       "pipeline: a run with these parameters needs %zu bytes, the arena has %zu",
                       run_bytes(budget_, params), room);
  params_ = params;
  return {};
}

Status Pipeline::prepare(ConstGray8View left, const PipelineRequest& req,
                         PipelineOutput& out) const {
  const int W = budget_.image_width, H = budget_.image_height;
  if (left.width() != W || left.height() != H)
    return Error::make(Errc::invalid_argument, "pipeline: left image %dx%d, calibration %dx%d",
                       left.width(), left.height(), W, H);
  if (req.method == MatchMethod::graph_cut && !budget_.graph_cut)
    return Error::make(Errc::invalid_argument,
                       "pipeline: method graph-cut, but its memory was not reserved at create "
                       "(PipelineBudget::graph_cut)");
  if (req.planes < 1 || req.planes > kMaxClasses)
    return Error::make(Errc::out_of_range, "pipeline: c = %d planes, must be 1..%d", req.planes,
                       kMaxClasses);
  if (!req.roi.inside(W, H))
    return Error::make(Errc::out_of_range, "pipeline: ROI (%d,%d %dx%d) not inside the %dx%d image",
                       req.roi.x, req.roi.y, req.roi.w, req.roi.h, W, H);
  if (req.has_click && !req.roi.contains(req.click_u, req.click_v))
    return Error::make(Errc::out_of_range, "pipeline: click (%d, %d) outside the ROI (%d,%d %dx%d)",
                       req.click_u, req.click_v, req.roi.x, req.roi.y, req.roi.w, req.roi.h);
  auto rroi = rectifier_.roi_to_rectified(StereoSide::left, req.roi);
  if (!rroi) return rroi.error();
  const Rect roi = *rroi;
  out.roi_rectified = roi;
  if (roi.w > budget_.max_roi_width || roi.h > budget_.max_roi_height)
    return Error::make(Errc::capacity_exceeded,
                       "pipeline: ROI is %dx%d px rectified, the budget allows %dx%d", roi.w, roi.h,
                       budget_.max_roi_width, budget_.max_roi_height);
  if (req.has_click) {
    auto c = rectifier_.to_rectified(StereoSide::left, {req.click_u + 0.0, req.click_v + 0.0});
    if (!c) return c.error();
    out.click_rectified = {true, static_cast<int>(std::lround(c->x())),
                           static_cast<int>(std::lround(c->y()))};
    if (!roi.contains(out.click_rectified.u, out.click_rectified.v))
      return Error::make(Errc::out_of_range,
                         "pipeline: click (%d, %d) maps outside the rectified ROI", req.click_u,
                         req.click_v);
  }
  return {};
}

namespace {

// The back half's share of the operator's request.
ReconstructionRequest reconstruction_request(const PipelineRequest& req,
                                             const PipelineOutput& out) {
  ReconstructionRequest r;
  r.planes = req.planes;
  r.click = out.click_rectified;
  r.reach = req.reach;
  return r;
}

}  // namespace

Result<PipelineOutput> Pipeline::run_with_disparity(ConstGray8View left,
                                                    ConstDisparityMap disparity,
                                                    const PipelineRequest& req,
                                                    const StepClock& clock) {
  if (arena_ == nullptr) return Error::make(Errc::not_ready, "pipeline: not created");
  Arena& arena = *arena_;
  arena.release_to(run_mark_);
  PipelineOutput out;
  PETRA_TRY(prepare(left, req, out));
  const Rect& roi = out.roi_rectified;
  if (!(disparity.roi == roi) || disparity.q4.width() != roi.w || disparity.q4.height() != roi.h)
    return Error::make(
        Errc::invalid_argument,
        "pipeline: disparity covers (%d,%d %dx%d), the ROI is (%d,%d %dx%d) rectified",
        disparity.roi.x, disparity.roi.y, disparity.q4.width(), disparity.q4.height(), roi.x, roi.y,
        roi.w, roi.h);
  auto lbuf = arena.allocate<std::uint8_t>(image_bytes(budget_), "rectified left");
  if (!lbuf) return lbuf.error();
  const Gray8View rl(lbuf->data(), budget_.image_width, budget_.image_height);
  out.left_rectified = rl;
  PETRA_TRY(checkpoint(clock, PipelineStep::rectify));
  {
    StepTimer timer(clock, out.timings, PipelineStep::rectify);
    PETRA_TRY(rectifier_.rectify(StereoSide::left, left, rl, roi));
  }
  out.disparity = disparity;
  const ReconstructionRequest rr_req = reconstruction_request(req, out);
  auto r = reconstruct(rectifier_.rig(), rectifier_.geometry(), disparity, rr_req,
                       params_.reconstruction, recon_budget(budget_), arena, clock, out.timings);
  if (!r) return r.error();
  out.result = *r;
  return out;
}

namespace {

struct RectifiedViews {
  Gray8View left, right;  // whole images; valid over the ROI and the right search area
};

// Rectifies the ROI and the right search area of the whole envelope (the
// range search's) into whole-image buffers from the arena.
Result<RectifiedViews> rectify_pair(const Rectifier& rectifier, const PipelineBudget& budget,
                                    ConstGray8View left, ConstGray8View right, Rect roi,
                                    Rect right_rectified, Arena& arena, const StepClock& clock,
                                    PipelineOutput& out) {
  const int W = budget.image_width, H = budget.image_height;
  auto lbuf = arena.allocate<std::uint8_t>(image_bytes(budget), "rectified left");
  if (!lbuf) return lbuf.error();
  auto rbuf = arena.allocate<std::uint8_t>(image_bytes(budget), "rectified right");
  if (!rbuf) return rbuf.error();
  const RectifiedViews pair{Gray8View(lbuf->data(), W, H), Gray8View(rbuf->data(), W, H)};
  out.left_rectified = pair.left;
  PETRA_TRY(checkpoint(clock, PipelineStep::rectify));
  StepTimer timer(clock, out.timings, PipelineStep::rectify);
  PETRA_TRY(rectifier.rectify(StereoSide::left, left, pair.left, roi));
  if (right_rectified.empty())
    return Error::make(Errc::out_of_range, "pipeline: no right search area for the ROI");
  PETRA_TRY(rectifier.rectify(StereoSide::right, right, pair.right, right_rectified));
  return pair;
}

// A drifted pair's right view rectified again with its rows moved by the
// offset the check measured (a rotation of the rig about its baseline, which
// the pair itself tells): the matcher then sees aligned rows. The check's
// figures stay the measured ones; its verdict becomes `corrected`.
Status correct_drift(const Rectifier& rectifier, ConstGray8View right, const RectifiedViews& pair,
                     Rect right_rectified, const CalibCheckParams& params, CalibCheck& check) {
  if (!params.correct_drift || check.verdict != CalibVerdict::drifted) return ok_status();
  const int rows_q4 =
      static_cast<int>(std::lround(check.vertical_offset_px * (1 << kRemapFracBits)));
  PETRA_TRY(
      rectifier.rectify_rows_moved(StereoSide::right, right, pair.right, right_rectified, rows_q4));
  check.corrected_px = rows_q4 / static_cast<double>(1 << kRemapFracBits);
  check.verdict = CalibVerdict::corrected;
  return ok_status();
}

// The disparity range for the fine matcher, within the budget.
Status disparity_range_step(const RectifiedViews& pair, Rect roi, const PipelineParams& params,
                            const PipelineBudget& budget, Arena& arena, const StepClock& clock,
                            PipelineOutput& out) {
  PETRA_TRY(checkpoint(clock, PipelineStep::disparity_range));
  {
    StepTimer timer(clock, out.timings, PipelineStep::disparity_range);
    auto r = find_disparity_range(pair.left, pair.right, roi, params.range, params.match, arena);
    if (!r) return r.error();
    out.range = *r;
  }
  if (out.range.max_px - out.range.min_px + 1 > budget.max_disparities)
    return Error::make(Errc::capacity_exceeded,
                       "pipeline: disparity range %d..%d px exceeds the budget of %d disparities",
                       out.range.min_px, out.range.max_px, budget.max_disparities);
  return {};
}

// Shadow masks: the left over the ROI (into out), the right over its search
// area at the matcher's range (returned).
Result<ShadowMask> shadow_step(const RectifiedViews& pair, Rect roi, const MatchDpParams& mp,
                               double shadow_fraction, Arena& arena, const StepClock& clock,
                               PipelineOutput& out) {
  const RightShadowWindows right_windows =
      right_shadow_windows(roi, mp.disp_min, mp.disp_max, pair.right.width());
  const Rect right_area = right_windows.mask;
  auto lmask = arena.allocate<std::uint8_t>(
      static_cast<std::size_t>(roi.w) * static_cast<std::size_t>(roi.h), "left shadow mask");
  if (!lmask) return lmask.error();
  auto rmask = arena.allocate<std::uint8_t>(
      static_cast<std::size_t>(right_area.w) * static_cast<std::size_t>(right_area.h),
      "right shadow mask");
  if (!rmask) return rmask.error();
  PETRA_TRY(checkpoint(clock, PipelineStep::shadow));
  StepTimer timer(clock, out.timings, PipelineStep::shadow);
  auto tl = shadow_threshold(pair.left, roi, shadow_fraction);
  if (!tl) return tl.error();
  out.shadow_left = *tl;
  auto nl = shadow_mask(pair.left, roi, tl->threshold, Gray8View(lmask->data(), roi.w, roi.h));
  if (!nl) return nl.error();
  out.left_shadow = {ImageView<const std::uint8_t>(lmask->data(), roi.w, roi.h), roi};
  auto tr = shadow_threshold(pair.right, right_windows.histogram, shadow_fraction);
  if (!tr) return tr.error();
  out.shadow_right = *tr;
  auto nr = shadow_mask(pair.right, right_area, tr->threshold,
                        Gray8View(rmask->data(), right_area.w, right_area.h));
  if (!nr) return nr.error();
  return ShadowMask{ImageView<const std::uint8_t>(rmask->data(), right_area.w, right_area.h),
                    right_area};
}

// Fine matching over the ROI by the requested method, into a disparity map
// from the arena; the matcher's state and scratch end with the step.
Result<DisparityMap> match_step(const RectifiedViews& pair, const ShadowMask& right_shadow,
                                Rect roi, MatchMethod method, const MatchDpParams& mp,
                                const PipelineParams& params, const PipelineBudget& budget,
                                Arena& arena, const StepClock& clock, PipelineOutput& out) {
  auto q4 = arena.allocate<std::int16_t>(
      static_cast<std::size_t>(roi.w) * static_cast<std::size_t>(roi.h), "disparity");
  if (!q4) return q4.error();
  DisparityMap disp{ImageView<std::int16_t>(q4->data(), roi.w, roi.h), roi};
  PETRA_TRY(checkpoint(clock, PipelineStep::match));
  StepTimer timer(clock, out.timings, PipelineStep::match);
  const ArenaScope step(arena);
  StereoInput in;
  in.left = pair.left;
  in.right = pair.right;
  in.left_shadow = &out.left_shadow;
  in.right_shadow = &right_shadow;
  out.method = method;
  if (method == MatchMethod::graph_cut) {
    GraphCutParams gp = params.graph_cut;
    gp.disp_min = mp.disp_min;
    gp.disp_max = mp.disp_max;
    gp.cancel = &clock;  // the caller's cancel is seen between expansions, not only steps
    // Its state for this ROI (or band) and range, released on return.
    auto st = match_graph_cut_bands(in, roi, gp, budget.graph_cut_bands, arena, disp);
    if (!st) return st.error();
    out.graph_cut = *st;
    auto refined = refine_subpixel(in, params.subpixel, disp);
    if (!refined) return refined.error();
    out.subpixel_refined = *refined;
  } else {
    const MatchBudget mb{budget.max_roi_width, budget.max_roi_height, budget.max_disparities};
    auto st = match_dp(in, roi, mp, mb, arena, disp);
    if (!st) return st.error();
    out.match = *st;
  }
  return disp;
}

// Photometric refinement of the accepted planes on the rectified pair; with
// the arm's reach, the discs it left chosen again on the refined planes.
Status refinement_step(const RectifiedPair& geometry, const RectifiedViews& pair,
                       Rect right_rectified, const PipelineParams& params, const DiscReach* reach,
                       const Eigen::Vector3d& camera, Arena& arena, const StepClock& clock,
                       PipelineOutput& out) {
  PETRA_TRY(checkpoint(clock, PipelineStep::plane_refinement));
  StepTimer timer(clock, out.timings, PipelineStep::plane_refinement);
  PlaneMove moves[kMaxClasses];
  auto n = refine_grind_planes_photometric(geometry, pair.left, pair.right, right_rectified,
                                           params.photometric, out.result, arena, moves);
  if (!n) return n.error();
  out.planes_refined = *n;
  if (reach == nullptr) return {};
  auto again = footprints_after_refinement(moves, params.reconstruction.grind, *reach, camera,
                                           out.result, arena);
  if (!again) return again.error();
  out.footprints_again = *again;
  return {};
}

}  // namespace

Result<PipelineOutput> Pipeline::run(ConstGray8View left, ConstGray8View right,
                                     const PipelineRequest& req, const StepClock& clock) {
  if (arena_ == nullptr) return Error::make(Errc::not_ready, "pipeline: not created");
  Arena& arena = *arena_;
  arena.release_to(run_mark_);
  const int W = budget_.image_width, H = budget_.image_height;
  if (right.width() != W || right.height() != H)
    return Error::make(Errc::invalid_argument, "pipeline: right image %dx%d, calibration %dx%d",
                       right.width(), right.height(), W, H);
  PipelineOutput out;
  last_calibration_ = {};
  PETRA_TRY(prepare(left, req, out));
  const Rect roi = out.roi_rectified;

  // The right image is rectified (and valid) over the ROI's search envelope.
  const Rect right_rectified =
      right_search_area(roi, params_.range.search_min_px, params_.range.search_max_px, W);
  auto pair =
      rectify_pair(rectifier_, budget_, left, right, roi, right_rectified, arena, clock, out);
  if (!pair) return pair.error();
  PETRA_TRY(disparity_range_step(*pair, roi, params_, budget_, arena, clock, out));
  // Row alignment of the rectified pair over the range just found.
  {
    StepTimer timer(clock, out.timings, PipelineStep::calibration_check);
    auto c = check_calibration(pair->left, pair->right, roi, right_rectified, out.range.min_px,
                               out.range.max_px, params_.calib_check, arena);
    if (!c) return c.error();
    out.calibration = last_calibration_ = *c;
    PETRA_TRY(correct_drift(rectifier_, right, *pair, right_rectified, params_.calib_check,
                            out.calibration));
    last_calibration_ = out.calibration;
  }
  MatchDpParams mp = params_.match;
  mp.disp_min = out.range.min_px;
  mp.disp_max = out.range.max_px;

  auto right_shadow = shadow_step(*pair, roi, mp, params_.shadow_fraction, arena, clock, out);
  if (!right_shadow) return right_shadow.error();
  if (out.click_rectified.present &&
      out.left_shadow.is_shadow(out.click_rectified.u, out.click_rectified.v))
    return Error::make(Errc::no_solution,
                       "pipeline: click (%d, %d) is on shadow: no 3-D point there", req.click_u,
                       req.click_v);
  auto disp =
      match_step(*pair, *right_shadow, roi, req.method, mp, params_, budget_, arena, clock, out);
  if (!disp) return disp.error();
  out.disparity = *disp;

  // Disparity to ranked planes.
  const ReconstructionRequest rr_req = reconstruction_request(req, out);
  auto r = reconstruct(rectifier_.rig(), rectifier_.geometry(), *disp, rr_req,
                       params_.reconstruction, recon_budget(budget_), arena, clock, out.timings);
  if (!r) return r.error();
  out.result = *r;
  PETRA_TRY(refinement_step(rectifier_.geometry(), *pair, right_rectified, params_, req.reach,
                            camera_centre_world(rectifier_.rig().left), arena, clock, out));
  return out;
}

}  // namespace petra
