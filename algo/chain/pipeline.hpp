// The whole onboard chain, from a stereo pair and an operator's request to
// ranked grind planes (docs/method.md 0-4), as one object the executive (fsw) and
// the ground tool (`petra eval`) both drive:
//   rectify (ROI and search area) -> disparity range (coarse match)
//   -> calibration check (row offset of matched corners; algo/camera/calib_check)
//   -> shadow masks -> match (dp or graph cut) -> reconstruct (mean filter, triangulate,
//   Delaunay, mesh filter, segmentation, grind planes; algo/chain/reconstruction).
// Memory: one caller arena. create() takes the remap tables from it (init);
// every run() releases the arena back to that point and takes what the run
// needs; outputs are views into the arena, valid until the next run().
// Pipeline::arena_bytes(budget, params) is the exact bound to allocate at init;
// Pipeline::memory() gives it per stage (docs/memory.md, `petra budget`).
// The graph-cut matcher's state (GraphCutMatcher::bytes_needed, about 200 B
// per ROI pixel) is taken per run in the matching step's place, as the DP's
// scratch is, and released before reconstruction: the two never coexist.
// Time: per-step timings through the caller's clock (algo makes no OS calls).
#pragma once

#include <cstddef>

#include "algo/camera/calib_check.hpp"
#include "algo/camera/camera_model.hpp"
#include "algo/camera/rectify.hpp"
#include "algo/chain/grind_plane_photometric.hpp"
#include "algo/chain/grind_plane_reach.hpp"
#include "algo/chain/pipeline_request.hpp"
#include "algo/chain/reconstruction.hpp"
#include "algo/core/arena.hpp"
#include "algo/core/chain_defaults.hpp"
#include "algo/core/result.hpp"
#include "algo/core/step_clock.hpp"
#include "algo/stereo/disparity_range.hpp"
#include "algo/stereo/disparity_subpixel.hpp"
#include "algo/stereo/match_dp.hpp"
#include "algo/stereo/match_graphcut.hpp"
#include "algo/stereo/match_graphcut_bands.hpp"
#include "algo/stereo/shadow.hpp"

namespace petra {

// Sizes fixed at init; inputs beyond them are refused with a named error.
struct PipelineBudget {
  int image_width = 1024;  // px, must equal calib.json's
  int image_height = 768;
  int max_roi_width = 640;  // px, ROI in the rectified left image
  int max_roi_height = 480;
  int max_disparities = 160;  // fine matcher: disp_max - disp_min + 1
  // 3-D points; 0 = one per 2 x 2 ROI pixels (more valid disparities: a
  // stride of 2 or more, ReconstructionStats::point_stride).
  std::size_t max_points = 0;
  // Room for the graph-cut matcher (MatchMethod::graph_cut) in the matching
  // step; the DP matcher is always available (the range search uses it).
  bool graph_cut = false;
  // The graph cut over bands of rows (algo/stereo/match_graphcut_bands): its memory
  // grows with the ROI width times the band instead of the whole ROI.
  GraphCutBands graph_cut_bands{};
};
Status validate(const PipelineBudget& b);
std::size_t points_of(const PipelineBudget& b);  // the 3-D points budget

struct PipelineParams {
  // Expected shadow share of the ROI (docs/method.md 1), [0, 1).
  double shadow_fraction = kShadowFraction;
  RangeSearchParams range;
  CalibCheckParams calib_check;  // row alignment of the rectified pair, after the range search
  MatchDpParams match;           // disp_min/max are set per run by the range search
  GraphCutParams graph_cut;      // disp_min/max likewise
  SubpixelParams subpixel;       // refines the graph cut's whole-pixel labels
  ReconstructionParams reconstruction;
  // Each ranked grind plane refined on the gray levels of both images
  // (algo/surface/plane_photometric), whichever matcher: on steep, weakly lit faces
  // the DP's staircases and the graph cut's stairs tilt the mesh's plane.
  PhotometricPlaneParams photometric;
};
Status validate(const PipelineParams& p);

struct PipelineOutput {
  ReconstructionOutput result;  // planes, ground, cloud, mesh, stats
  Rect roi_rectified;
  ClickPx click_rectified;
  ConstGray8View left_rectified;  // full size; valid inside roi_rectified
  ShadowMask left_shadow;         // over roi_rectified
  ShadowThreshold shadow_left, shadow_right;
  DisparityRange range;
  CalibCheck calibration;       // present when the pair was matched (not on a replayed map)
  ConstDisparityMap disparity;  // matcher output before the mean filter
  MatchMethod method = MatchMethod::dp;  // the matcher that made `disparity`
  MatchDpStats match;                    // method dp
  GraphCutReport graph_cut;              // method graph_cut
  long subpixel_refined = 0;             // graph-cut pixels given a sub-pixel value
  int planes_refined = 0;                // accepted grind planes refined photometrically
  int footprints_again = 0;  // planes whose disc the arm left on refinement, chosen again
  StepTimings timings;
};

// Arena bytes per stage for a budget (Pipeline::memory). Kept: the run's
// buffers that live to its end; the four steps run one after another in the
// space after them, so the run needs kept + the largest step.
struct PipelineMemory {
  std::size_t tables = 0;           // init: the two remap tables (4 B per image pixel each)
  std::size_t rectified = 0;        // kept: the rectified pair (whole images)
  std::size_t masks_disparity = 0;  // kept: shadow masks, raw disparity
  std::size_t range = 0;            // step: coarse disparity-range search
  std::size_t calib_check = 0;      // step: the pair's vertical offset (algo/camera/calib_check)
  std::size_t match_dp = 0;         // step: DP matcher scratch
  std::size_t match_graph_cut = 0;  // step: graph-cut state (0 unless budget.graph_cut)
  std::size_t reconstruction = 0;   // step: cloud, mesh, segmentation, planes
  std::size_t refinement =
      0;                  // step (after reconstruction, which stays): photometric, then discs again
  std::size_t slack = 0;  // alignment padding
  std::size_t largest_step() const;
  std::size_t run() const;  // kept + largest step + slack
  std::size_t total() const { return tables + run(); }
};

class Pipeline {
 public:
  Pipeline() = default;

  static PipelineMemory memory(const PipelineBudget& budget, const PipelineParams& params);
  static std::size_t init_bytes(const PipelineBudget& budget);
  static std::size_t run_bytes(const PipelineBudget& budget, const PipelineParams& params);
  static std::size_t arena_bytes(const PipelineBudget& budget, const PipelineParams& params) {
    return init_bytes(budget) + run_bytes(budget, params);
  }

  // Validates everything and builds the remap tables in `arena`, which must
  // outlive the Pipeline and hold arena_bytes(budget, params).
  static Result<Pipeline> create(const StereoRig& rig, const PipelineBudget& budget,
                                 const PipelineParams& params, Arena& arena);

  // Parameters for the runs to come. The remap tables stay: they depend on
  // the rig and the budget only. Refused, the parameters in force kept, when
  // invalid or when a run with them needs more than the arena holds after
  // the tables. Outputs of the last run stay valid.
  Status set_params(const PipelineParams& params);

  Result<PipelineOutput> run(ConstGray8View left, ConstGray8View right,
                             const PipelineRequest& request, const StepClock& clock);

  // Replays a given disparity map (rectified left view: a ground truth, a
  // recorded or another matcher's map) through the back half only; the map
  // must cover exactly the request's rectified ROI. Left image for products.
  Result<PipelineOutput> run_with_disparity(ConstGray8View left, ConstDisparityMap disparity,
                                            const PipelineRequest& request, const StepClock& clock);

  // The last run's calibration check, kept when a later step refuses the run
  // (a drifted pair is often why); not present before a matched run.
  const CalibCheck& last_calibration() const { return last_calibration_; }
  const Rectifier& rectifier() const { return rectifier_; }
  const PipelineBudget& budget() const { return budget_; }
  const PipelineParams& params() const { return params_; }

 private:
  Status prepare(ConstGray8View left, const PipelineRequest& request, PipelineOutput& out) const;

  Arena* arena_ = nullptr;
  std::size_t run_mark_ = 0;
  Rectifier rectifier_;
  PipelineBudget budget_;
  PipelineParams params_;
  std::size_t max_points_ = 0;
  CalibCheck last_calibration_;
};

}  // namespace petra
