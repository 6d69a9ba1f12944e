#include "algo/propose/proposer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace petra {

const char* proposal_note_name(ProposalNote note) {
  switch (note) {
    case ProposalNote::ok:
      return "ok";
    case ProposalNote::no_grindable_plane:
      return "no_grindable_plane";
    case ProposalNote::chain_refused:
      return "chain_refused";
    case ProposalNote::unreachable:
      return "unreachable";
  }
  return "unknown";
}

namespace {

bool weight_ok(double w) {
  return w >= 0.0 && w <= 1.0;  // false for NaN
}

DetectionBudget detection_budget(const ProposerBudget& b, const PipelineParams& params) {
  DetectionBudget d;
  d.image_width = b.pipeline.image_width;
  d.image_height = b.pipeline.image_height;
  d.factor = b.detection_factor;
  d.search_min_px = params.range.search_min_px;
  d.search_max_px = params.range.search_max_px;
  return d;
}

double clamp01(double x) {
  return std::clamp(x, 0.0, 1.0);
}

}  // namespace

Status validate(const ProposerBudget& b) {
  PETRA_TRY(validate(b.pipeline));
  if (b.max_roi_width < 16 || b.max_roi_width > b.pipeline.image_width || b.max_roi_height < 16 ||
      b.max_roi_height > b.pipeline.image_height)
    return Error::make(Errc::invalid_argument,
                       "proposer: max ROI %dx%d not within 16 px..the image", b.max_roi_width,
                       b.max_roi_height);
  if (b.max_evaluated < 1 || b.max_evaluated > kMaxProposals)
    return Error::make(Errc::invalid_argument, "proposer: max_evaluated %d not within 1..%d",
                       b.max_evaluated, kMaxProposals);
  return {};
}

Status validate(const ProposalRequest& r, int width, int height) {
  if (!r.region.empty() && !r.region.inside(width, height))
    return Error::make(Errc::out_of_range, "region: (%d,%d %dx%d) is not inside the %dx%d image",
                       r.region.x, r.region.y, r.region.w, r.region.h, width, height);
  if (r.region.w < 0 || r.region.h < 0)
    return Error::make(Errc::out_of_range, "region: negative size %dx%d", r.region.w, r.region.h);
  if (r.max_proposals < 1 || r.max_proposals > kMaxProposals)
    return Error::make(Errc::out_of_range, "max_proposals: %d not within 1..%d", r.max_proposals,
                       kMaxProposals);
  const ProposalWeights& w = r.weights;
  const struct {
    const char* name;
    double value;
  } terms[] = {{"weights.grindable", w.grindable},
               {"weights.reach", w.reach},
               {"weights.certainty", w.certainty},
               {"weights.size", w.size}};
  for (const auto& t : terms)
    if (!weight_ok(t.value))
      return Error::make(Errc::out_of_range, "%s: %g not within 0..1", t.name, t.value);
  if (w.grindable + w.reach + w.certainty + w.size <= 0.0)
    return Error::make(Errc::out_of_range, "weights: all four are 0");
  return {};
}

ProposalScore score_plane(const GrindPlane* best, bool reachable, double footprint_diameter_mm,
                          const GrindParams& grind, const ProposalWeights& w) {
  ProposalScore s;
  if (best == nullptr) return s;
  if (best->verdict == PlaneVerdict::accepted)
    s.grindable = 1.0 - 0.5 * clamp01(best->footprint_rms_mm / grind.max_footprint_rms_mm);
  s.reach = reachable ? 1.0 : 0.0;
  s.certainty = 1.0 - 0.5 * (clamp01(best->normal_sigma_deg / grind.max_normal_sigma_deg) +
                             clamp01(best->offset_sigma_mm / grind.max_offset_sigma_mm));
  const double disc = std::numbers::pi / 4.0 * footprint_diameter_mm * footprint_diameter_mm;
  s.size = disc > 0 ? clamp01(best->area_mm2 / (4.0 * disc)) : 0.0;
  const double sum = w.grindable + w.reach + w.certainty + w.size;
  s.total = sum > 0 ? (w.grindable * s.grindable + w.reach * s.reach + w.certainty * s.certainty +
                       w.size * s.size) /
                          sum
                    : 0.0;
  return s;
}

std::size_t Proposer::detection_bytes(const ProposerBudget& b) {
  // The coarse envelope is widest when its minimum lies just below a multiple of the factor.
  DetectionBudget d = detection_budget(b, PipelineParams{});
  d.search_min_px = d.factor - 1;
  d.search_max_px = d.search_min_px + b.pipeline.max_disparities - 1;
  return detection_arena_bytes(d);
}

std::size_t Proposer::arena_bytes(const ProposerBudget& b, const PipelineParams& params) {
  return Pipeline::init_bytes(b.pipeline) +
         std::max(Pipeline::run_bytes(b.pipeline, params), detection_bytes(b));
}

Result<Proposer> Proposer::create(Pipeline& pipeline, const ProposerBudget& budget,
                                  const arm::ArmGeometry& geometry, const arm::JointLimits& limits,
                                  Arena& arena, const ProposerParams& proposer) {
  PETRA_TRY(validate(budget));
  PETRA_TRY(validate(proposer.detection));
  PETRA_TRY(validate(proposer.discs));
  PETRA_TRY(validate(detection_budget(budget, pipeline.params())));
  if (!(proposer.standoff_mm > 0.0 && proposer.standoff_mm <= 500.0))
    return Error::make(Errc::invalid_argument, "proposer: standoff %g mm not within (0, 500]",
                       proposer.standoff_mm);
  if (proposer.further_planes_c < 0 || proposer.further_planes_c > kMaxClasses)
    return Error::make(Errc::invalid_argument, "proposer: further_planes_c %d not within 0..%d",
                       proposer.further_planes_c, kMaxClasses);
  const PipelineBudget& pb = pipeline.budget();
  if (pb.image_width != budget.pipeline.image_width ||
      pb.image_height != budget.pipeline.image_height ||
      pb.max_roi_width != budget.pipeline.max_roi_width ||
      pb.max_roi_height != budget.pipeline.max_roi_height)
    return Error::make(Errc::invalid_argument,
                       "proposer: the pipeline is built for %dx%d images, ROI %dx%d; the budget "
                       "says %dx%d, ROI %dx%d",
                       pb.image_width, pb.image_height, pb.max_roi_width, pb.max_roi_height,
                       budget.pipeline.image_width, budget.pipeline.image_height,
                       budget.pipeline.max_roi_width, budget.pipeline.max_roi_height);
  if (arena.remaining() < detection_bytes(budget))
    return Error::make(Errc::capacity_exceeded,
                       "proposer: arena holds %zu bytes after the tables, detection needs %zu",
                       arena.remaining(), detection_bytes(budget));
  Proposer out;
  out.rock_map_shape_ = rock_map_shape(detection_budget(budget, pipeline.params()));
  if (out.rock_map_shape_.cells() > sizeof(out.rock_map_))
    return Error::make(Errc::invalid_argument, "proposer: rock map of %zu cells",
                       out.rock_map_shape_.cells());
  out.pipeline_ = &pipeline;
  out.arena_ = &arena;
  out.space_mark_ = arena.mark();
  out.budget_ = budget;
  out.params_ = proposer;
  out.geometry_ = geometry;
  out.limits_ = limits;
  return out;
}

namespace {

// The candidate's ROI cut to at most max_w x max_h (>= 16) around its
// centre, the click kept 8 px inside, within the image.
Rect cut_roi(Rect roi, int click_u, int click_v, int max_w, int max_h, int W, int H) {
  auto cut = [](int x, int w, int limit, int click, int image) {
    if (w <= limit) return std::pair{x, w};
    int nx = x + (w - limit) / 2;
    nx = std::clamp(nx, click - limit + 8, click - 8);  // the click 8 px inside
    nx = std::clamp(nx, 0, image - limit);
    return std::pair{nx, limit};
  };
  const auto [x, w] = cut(roi.x, roi.w, max_w, click_u, W);
  const auto [y, h] = cut(roi.y, roi.h, max_h, click_v, H);
  return {x, y, w, h};
}

}  // namespace

PipelineRequest Proposer::chain_request(const RockCandidate& rock) const {
  const PipelineBudget& pb = budget_.pipeline;
  PipelineRequest q;
  q.has_click = true;
  q.click_u = rock.click_u;
  q.click_v = rock.click_v;
  q.planes = kProposalPlanesC;
  q.method = MatchMethod::dp;
  int max_w = budget_.max_roi_width, max_h = budget_.max_roi_height;
  q.roi = cut_roi(rock.roi, q.click_u, q.click_v, max_w, max_h, pb.image_width, pb.image_height);
  // Rectified, an ROI near the image's corners grows: cut it by the excess.
  for (int attempt = 0; attempt < 4; ++attempt) {
    auto r = pipeline_->rectifier().roi_to_rectified(StereoSide::left, q.roi);
    if (!r || (r->w <= pb.max_roi_width && r->h <= pb.max_roi_height)) break;
    max_w = std::max(16, std::min(q.roi.w, q.roi.w - (r->w - pb.max_roi_width) - 1));
    max_h = std::max(16, std::min(q.roi.h, q.roi.h - (r->h - pb.max_roi_height) - 1));
    q.roi = cut_roi(q.roi, q.click_u, q.click_v, max_w, max_h, pb.image_width, pb.image_height);
  }
  return q;
}

bool PlaneCandidates::add(const GrindPlane& p, const GrindParams& grind) {
  if (count >= kMaxCandidates) return false;
  for (int k = 0; k < count; ++k)
    if (same_face(planes[k], p, grind)) return false;
  planes[count] = p;
  if (p.verdict == PlaneVerdict::surplus) planes[count].verdict = PlaneVerdict::accepted;
  ++count;
  return true;
}

bool PlaneCandidates::flat(const GrindPlane& p, const GrindParams& grind) {
  return p.rms_mm <= grind.max_footprint_rms_mm;
}

void PlaneCandidates::keep_flat(int first, const GrindParams& grind) {
  int n = first;
  for (int k = first; k < count; ++k)
    if (flat(planes[k], grind)) planes[n++] = planes[k];
  count = n;
}

void planes_on_other_rocks(const ReconstructionOutput& r, const RockOnMap& rock,
                           bool (&neighbour)[kMaxClasses]) {
  long own[kMaxClasses] = {}, other[kMaxClasses] = {};
  for (std::size_t i = 0; i < r.pixels.size(); ++i) {
    const int k = r.vertex_class[i] - kVertexPlane0;
    if (k < 0 || k >= kMaxClasses) continue;
    const std::uint8_t at = rock.at(r.pixels[i].u, r.pixels[i].v);
    if (at == rock.index)
      ++own[k];
    else if (at != kNoRock)
      ++other[k];
  }
  for (int k = 0; k < kMaxClasses; ++k) neighbour[k] = other[k] > own[k];
}

// The proposal's planes (kMaxProposalPlanes at most), from this rock's
// candidates in order: the chain's accepted planes, its surplus ones
// (qualified, past the run's c = 3, which a neighbour's planes in the ROI
// also take), then the further pass's accepted planes (further_planes), each
// not of the same face as an earlier one; a surplus plane not kept (the same
// face as an earlier one, or a patch rougher than the footprint's tolerance,
// which keep_flat would drop) leaves its triangles to the further pass. The
// reachable ones first, each group in that order, then the rock's refused
// planes that say why. A neighbour's planes are left to its own run.
Status Proposer::own_planes(int index, const PipelineOutput& out, const ArmReach& reach,
                            RockProposal& proposal) {
  const GrindResult& g = out.result.planes;
  const GrindParams& gp = pipeline_->params().reconstruction.grind;
  bool neighbour[kMaxClasses] = {}, taken[kMaxClasses] = {};
  const RockMapShape& m = rock_map_shape_;
  const RockOnMap rock{std::span<const std::uint8_t>(rock_map_, m.cells()), m.w,
                       budget_.detection_factor * m.step, index};
  planes_on_other_rocks(out.result, rock, neighbour);
  PlaneCandidates& c = candidates_;
  c.count = 0;
  for (int k = 0; k < g.count; ++k)
    if (!neighbour[k] && g.planes[k].verdict == PlaneVerdict::accepted) {
      c.add(g.planes[k], gp);
      taken[k] = true;
    }
  const int chain_accepted = c.count;
  bool on_rock[kMaxClasses] = {};
  planes_mostly_on(out.result, rock, on_rock);
  for (int k = 0; k < g.count; ++k)
    if (on_rock[k] && g.planes[k].verdict == PlaneVerdict::surplus &&
        PlaneCandidates::flat(g.planes[k], gp)) {
      taken[k] = c.add(g.planes[k], gp) && !neighbour[k];
    }
  if (params_.further_planes_c > 0) {
    const Rectifier& rect = pipeline_->rectifier();
    auto f = further_planes(rect.rig(), rect.geometry(), pipeline_->params().reconstruction,
                            out.result, rock, taken, params_.further_planes_c, &reach, *arena_);
    if (!f && f.code() != Errc::degenerate) return f.error();
    for (int k = 0; f && k < f->accepted; ++k) c.add(f->planes[k], gp);  // degenerate: none
  }
  if (params_.flat_discs) {
    const Rectifier& rect = pipeline_->rectifier();
    auto d = flat_discs(rect.rig(), rect.geometry(), pipeline_->params().reconstruction, out.result,
                        rock, taken,
                        std::span<const GrindPlane>(c.planes, static_cast<std::size_t>(c.count)),
                        params_.discs, &reach, *arena_);
    if (!d) return d.error();
    for (int k = 0; k < d->accepted; ++k) c.add(d->planes[k], gp);
  }
  c.keep_flat(chain_accepted, gp);
  arm::ArmReason why[PlaneCandidates::kMaxCandidates];
  for (int k = 0; k < c.count; ++k) why[k] = reach.why(c.planes[k].centroid_mm, c.planes[k].normal);
  int n = 0;
  for (int pass = 0; pass < 2; ++pass)  // reachable first, then the others
    for (int k = 0; k < c.count && n < kMaxProposalPlanes; ++k)
      if ((why[k] == arm::ArmReason::ok) == (pass == 0)) {
        proposal.reach[n] = why[k];
        proposal.planes[n++] = c.planes[k];
      }
  for (int k = 0; k < g.count && n < kMaxProposalPlanes; ++k) {
    const PlaneVerdict v = g.planes[k].verdict;
    if (!neighbour[k] && v != PlaneVerdict::accepted && v != PlaneVerdict::surplus) {
      proposal.reach[n] = reach.why(g.planes[k].centroid_mm, g.planes[k].normal);
      proposal.planes[n++] = g.planes[k];
    }
  }
  proposal.plane_count = n;
  return {};
}

Result<PipelineOutput> Proposer::run_chain(ConstGray8View left, ConstGray8View right,
                                           const PipelineRequest& q, const StepClock& clock,
                                           const ConstDisparityMap* given) {
  if (given == nullptr) return pipeline_->run(left, right, q, clock);
  auto roi = pipeline_->rectifier().roi_to_rectified(StereoSide::left, q.roi);
  if (!roi) return roi.error();
  const Rect inside{roi->x - given->roi.x, roi->y - given->roi.y, roi->w, roi->h};
  if (inside.x < 0 || inside.y < 0 || inside.x + inside.w > given->q4.width() ||
      inside.y + inside.h > given->q4.height())
    return Error::make(Errc::invalid_argument, "given: the map does not cover the ROI");
  return pipeline_->run_with_disparity(left, ConstDisparityMap(given->q4.sub(inside), *roi), q,
                                       clock);
}

Status Proposer::evaluate(ConstGray8View left, ConstGray8View right, int index,
                          const arm::JointVector& current, const ProposalWeights& weights,
                          const StepClock& clock, const ConstDisparityMap* given,
                          RockProposal& out) {
  const RockCandidate& rock = detection_.rocks[index];
  const ArmReach reach(geometry_, limits_, current, params_.standoff_mm);
  PipelineRequest q = chain_request(rock);
  q.reach = &reach;  // as SELECT_ROI's run: the footprints the arm reaches
  out = RockProposal{};
  out.rock = rock;
  out.rock.roi = q.roi;  // what SELECT_ROI sends back
  out.planes_c = q.planes;
  auto r = run_chain(left, right, q, clock, given);
  if (!r) {
    if (r.code() == Errc::cancelled) return r.error();
    out.note = ProposalNote::chain_refused;
    out.chain_error = r.error();
    return {};
  }
  PETRA_TRY(own_planes(index, *r, reach, out));
  const GrindResult& g = r->result.planes;
  const GrindPlane* best = nullptr;
  bool reachable = false, grindable_any = false;
  for (int k = 0; k < out.plane_count; ++k) {  // own_planes set each plane's reach
    const bool grindable = out.planes[k].verdict == PlaneVerdict::accepted;
    const bool offered = grindable && out.reach[k] == arm::ArmReason::ok;
    grindable_any = grindable_any || grindable;
    if (offered && !reachable) best = &out.planes[k], reachable = true;
    if (best == nullptr && grindable) best = &out.planes[k];
  }
  if (best == nullptr && out.plane_count > 0) best = &out.planes[0];
  out.note = reachable       ? ProposalNote::ok
             : grindable_any ? ProposalNote::unreachable
                             : ProposalNote::no_grindable_plane;
  out.score = score_plane(best, reachable, g.footprint_diameter_mm,
                          pipeline_->params().reconstruction.grind, weights);
  return {};
}

namespace {

// Offered proposals first, then by total score, then the larger rock.
bool ranks_before(const RockProposal& a, const RockProposal& b) {
  const bool ao = a.note == ProposalNote::ok, bo = b.note == ProposalNote::ok;
  if (ao != bo) return ao;
  if (a.score.total != b.score.total) return a.score.total > b.score.total;
  return a.rock.pixels > b.rock.pixels;
}

// Why no proposal is offered (static text).
const char* empty_reason(const RockProposal* items, int n) {
  if (n == 0) return "no rock stands out of the ground";
  bool any_ran = false, any_grindable = false;
  for (int i = 0; i < n; ++i) {
    any_ran = any_ran || items[i].note != ProposalNote::chain_refused;
    any_grindable = any_grindable || items[i].note == ProposalNote::unreachable;
  }
  if (!any_ran) return "the chain refused every rock found";
  if (!any_grindable) return "no rock found has a grindable face";
  return "no grindable face is within the arm's reach";
}

}  // namespace

void Proposer::rank(const ProposalRequest& request, int evaluated) {
  int order[kMaxProposals] = {};
  for (int i = 0; i < evaluated; ++i) order[i] = i;
  // Insertion sort: stable, at most kMaxProposals, no heap (std::stable_sort takes a buffer).
  for (int i = 1; i < evaluated; ++i)
    for (int j = i; j > 0 && ranks_before(evaluated_[order[j]], evaluated_[order[j - 1]]); --j)
      std::swap(order[j], order[j - 1]);
  list_ = ProposalList{};
  list_.candidates = detection_.count;
  list_.count = std::min(evaluated, request.max_proposals);
  for (int i = 0; i < list_.count; ++i) list_.items[i] = evaluated_[order[i]];
  if (evaluated == 0 || evaluated_[order[0]].note != ProposalNote::ok)
    list_.empty_reason = empty_reason(evaluated_, evaluated);
}

Result<const ProposalList*> Proposer::run(ConstGray8View left, ConstGray8View right,
                                          const ProposalRequest& request,
                                          const arm::JointVector& current, const StepClock& clock,
                                          const ConstDisparityMap* given) {
  if (arena_ == nullptr) return Error::make(Errc::not_ready, "proposer: not created");
  const PipelineBudget& pb = budget_.pipeline;
  PETRA_TRY(validate(request, pb.image_width, pb.image_height));
  if (!current.allFinite())
    return Error::make(Errc::invalid_argument, "current: the arm's pose is not finite");
  arena_->release_to(space_mark_);  // the last run's chain outputs
  auto d = detect_rocks(pipeline_->rectifier(), left, right, request.region,
                        detection_budget(budget_, pipeline_->params()), params_.detection, *arena_,
                        clock, std::span<std::uint8_t>(rock_map_, rock_map_shape_.cells()));
  if (!d) return d.error();
  detection_ = *d;
  int evaluated = 0;
  for (int i = 0; i < detection_.count && evaluated < budget_.max_evaluated; ++i) {
    PETRA_TRY(
        evaluate(left, right, i, current, request.weights, clock, given, evaluated_[evaluated++]));
  }
  rank(request, evaluated);
  return &list_;
}

}  // namespace petra
