// Dense stereo by graph cuts with explicit occlusions (Kolmogorov & Zabih,
// ICCV 2001; the IPOL 2014 article by Kolmogorov, Monasse and Tan describes the
// method in detail). docs/graphcut.md explains the energy and our choices.
//
// An assignment a = (p, d) pairs left pixel p = (x, y) with right pixel
// q = (x - d, y). A configuration is a set of active assignments with at most
// one per left and one per right pixel (uniqueness); a pixel in none is
// occluded. Energy, in integer cost units of 1/4 gray level squared:
//   E = sum over active a of (D(a) - K)                      data + occlusion
//     + sum over neighbouring pairs {(p,d),(p',d)} of V * [exactly one active]
//   D = min(BT, clip)^2, BT = Birchfield-Tomasi distance of the gray values
//       (half-pixel samples towards the 4 neighbours, so it tolerates half a
//       pixel of sampling or vertical rectification error),
//   V = lambda1 if both |I_L(p)-I_L(p')| and |I_R(q)-I_R(q')| are below the
//       edge threshold, else lambda2 (smoothness drops across intensity edges).
// Parameters left at kAuto follow the original method: K = mean over pixels of
// the k-th smallest D (k = (#disparities+2)/4, at least 3), lambda = K/5,
// lambda1 = 3 lambda, lambda2 = lambda, threshold 8, clip 30.
// Minimised by alpha-expansion: for each disparity alpha (seeded random or
// fixed order) the best configuration reachable by deactivating assignments
// and activating assignments of disparity alpha is one min cut (algo/stereo/maxflow).
// The start is the scanline DP matcher's map (algo/stereo/match_dp), rounded and
// made unique (or a left-right checked 5x5 block matching of D, or all
// occluded as in the reference); guided cycles (default 1) restricted to a
// band of +-1 px around the start come first, then full cycles over all
// disparities until one brings no decrease or max_cycles (default 1).
//
// Shadow pixels (nonzero in a mask) are marked occluded: every assignment that
// touches a shadow pixel, left or right, is left out of the problem, so shadow
// pixels get no disparity (as docs/method.md 1 asks) and their neighbours are neither
// pulled towards nor pushed away from them by the smoothness term.
//
// Inputs:  StereoInput (algo/stereo/match_dp.hpp): rectified left/right gray images
//          of equal size (whole images: the right search strip and the
//          half-pixel samples may lie outside the ROI) and optional shadow
//          masks (algo/stereo/shadow.hpp); the ROI in the left image; the disparity
//          range [disp_min, disp_max] (d = x_left - x_right).
// Output:  DisparityMap over the ROI: Q4 disparities, kInvalidDisparity where
//          occluded or shadowed.
// Memory:  all from the Arena at init, for a budget (max ROI width, height,
//          disparity count): bytes_needed() =
//            195 B per ROI pixel (146 B of it the max-flow graph: up to two
//            nodes per pixel, 73 B each)
//            + 13 B per right strip pixel (height x (width + disparities - 1))
//            + match_dp_scratch_bytes of the same budget (the DP start).
//          Flight default 320 x 320 ROI, 128 disparities: 23.7 MB.
//          match() never allocates.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/core/arena.hpp"
#include "algo/core/disparity.hpp"
#include "algo/core/fixed_vector.hpp"
#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"
#include "algo/core/step_clock.hpp"
#include "algo/stereo/match_dp.hpp"
#include "algo/stereo/match_graphcut_terms.hpp"
#include "algo/stereo/maxflow.hpp"

namespace petra {

inline constexpr std::int32_t kGraphCutAuto = -1;
inline constexpr int kGraphCutMaxCycles = 32;

// One expansion as seen by an observer (tests and tools): labels are per ROI
// pixel, row-major, -1 occluded, else d - disp_min. The starting labelling
// is reported first, as a step of cycle -1.
struct GraphCutStep {
  int cycle = 0;
  int disparity = 0;
  bool skipped = false;  // nothing changed since this disparity's last expansion
  bool guided = false;   // restricted to the start's band (not optimal over every move)
  bool applied = false;  // the move decreased the energy and was taken
  std::int64_t energy_before = 0;
  std::int64_t energy_after = 0;
  std::span<const std::int16_t> labels;
  int width = 0;
  int height = 0;
};

struct GraphCutObserver {
  void (*on_expansion)(void* context, const GraphCutStep& step) = nullptr;
  void* context = nullptr;
};

// Where the expansions start. Not "everything occluded" (the reference's
// start), the expansions refine a labelling instead of building it, which is
// much faster: the scanline DP matcher's map (fast and more accurate than one
// cycle of expansions on it; falls back to block matching when the DP finds
// no match, e.g. too few edges), or a left-right checked 5x5 block matching
// of the data term; or a map the caller gives (a previous result to refine,
// or, in evaluation, the ground truth: docs/graphcut.md).
enum class GraphCutStart : std::uint8_t { occluded, block_matching, dp, given };

struct GraphCutParams {
  int disp_min = 0;
  int disp_max = 15;
  int max_cycles = 1;        // full cycles, 1..kGraphCutMaxCycles (docs/graphcut.md: why 1)
  bool random_order = true;  // a new seeded permutation of the disparities each cycle
  std::uint32_t seed = 1;
  std::int32_t occlusion_k = kGraphCutAuto;  // K > 0, cost units
  std::int32_t lambda = kGraphCutAuto;       // >= 0; default K/5
  std::int32_t lambda1 = kGraphCutAuto;      // >= 0; default 3 lambda
  std::int32_t lambda2 = kGraphCutAuto;      // >= 0; default lambda
  int edge_threshold = 8;                    // gray levels, 1..255
  int data_clip = 30;                        // gray levels, 1..90
  // The right view's gray levels mapped to the left's before the data term:
  // the DP's map of step 0, measured on its edge pairs (match_dp_gray_map
  // with dp_start's parameters; docs/graphcut.md).
  bool normalise_gray = true;
  // The labelling the expansions start from (docs/graphcut.md, "Start").
  GraphCutStart start = GraphCutStart::dp;
  // Parameters of the DP start (its disparity range is this one's).
  MatchDpParams dp_start{};
  // The given start: Q4 disparities over the ROI (roi.w x roi.h), rounded to
  // whole pixels and made unique as the DP's map is.
  ConstDisparityMap start_map{};
  // Guided cycles, run before the max_cycles full ones (not with the
  // occluded start): each expansion on alpha may change only pixels whose
  // starting disparity is within guided_radius of alpha, or that started
  // occluded. A much smaller graph per expansion brings the labelling near
  // a local minimum before the full cycles, which then change little.
  int guided_cycles = 1;  // 0..kGraphCutMaxCycles
  int guided_radius = 1;  // 0..kMaxDisparities px
  // Fixes, before each cut, the assignments whose choice is already decided
  // (an exact reduction: the minimum is unchanged). Off only to test it.
  bool prune = true;
  GraphCutObserver observer{};
  // Optional: polled (StepClock::cancelled()) before each expansion, so an
  // operator's ABORT ends a long match within one expansion (Errc::cancelled;
  // `out` is then left unchanged). Null: never cancelled.
  const StepClock* cancel = nullptr;
};

struct GraphCutBudget {
  int max_width = 320;
  int max_height = 320;
  int max_disparities = 128;
};

struct GraphCutReport {
  std::int32_t occlusion_k = 0;  // the parameters used (after automatic choice)
  std::int32_t lambda1 = 0;
  std::int32_t lambda2 = 0;
  int guided_cycles = 0;                          // guided cycles run (before the full ones)
  int cycles = 0;                                 // full cycles run
  int expansions = 0;                             // min cuts solved
  int expansions_skipped = 0;                     // provably unchanged, not solved
  bool converged = false;                         // the last cycle brought no decrease
  GraphCutStart start = GraphCutStart::occluded;  // the start used (dp may fall back)
  std::int64_t energy_start = 0;  // energy of the starting labelling (all occluded: 0)
  std::int64_t energy = 0;        // final energy
  FixedVector<std::int64_t, kGraphCutMaxCycles> cycle_energy;  // after each cycle
  std::int64_t graph_nodes = 0;  // summed over expansions (work measure)
  long matched_pixels = 0;
  long occluded_pixels = 0;
  long shadow_pixels = 0;
  int gray_gain_q8 = 256;  // the right view's gray-level map applied (1/256)
  int gray_offset_q8 = 0;  // its level(0), 1/256 gray level
};

class GraphCutMatcher {
 public:
  static std::size_t bytes_needed(const GraphCutBudget& budget);

  // Carves all state from `arena` (errors: budget out of range, arena too small).
  Status init(Arena& arena, const GraphCutBudget& budget);

  // Matches the ROI; `out.q4` must be roi.w x roi.h and `out.roi` is set to roi.
  Result<GraphCutReport> match(const StereoInput& in, Rect roi, const GraphCutParams& params,
                               DisparityMap& out);

  // The automatic K of these images and parameters (what match() would use
  // with occlusion_k left at kGraphCutAuto), for tools that report or scale it.
  Result<std::int32_t> automatic_occlusion_k(const StereoInput& in, Rect roi,
                                             const GraphCutParams& params);

  const GraphCutBudget& budget() const { return budget_; }

 private:
  using Sample = gc::Sample;
  // Per-pixel flags: edge to the right / lower neighbour, unusable (shadow).
  static constexpr std::uint8_t kEdgeRight = 1;
  static constexpr std::uint8_t kEdgeDown = 2;
  static constexpr std::uint8_t kUnusable = 4;
  static constexpr std::int16_t kOccluded = -1;

  Status validate(const StereoInput& in, Rect roi, const GraphCutParams& params,
                  const DisparityMap* out) const;
  Status prepare(const StereoInput& in, Rect roi, const GraphCutParams& params,
                 match::GrayMap* applied = nullptr);
  Result<match::GrayMap> right_gray_map(const StereoInput& in, Rect roi,
                                        const GraphCutParams& params);
  std::int32_t automatic_k() const;
  void block_matching_labels();
  // block_matching_labels()'s steps (match_graphcut_start.cpp).
  void block_cost_sums(int d);
  void take_block_winners(int di);
  void keep_agreeing_winners();
  // match()'s steps.
  Status choose_weights(const GraphCutParams& params, GraphCutReport& report);
  Result<std::int64_t> start_labels(const StereoInput& in, Rect roi, const GraphCutParams& params,
                                    GraphCutReport& report);
  void notify(const GraphCutParams& params, GraphCutStep& step) const;
  void shuffle_order(const GraphCutParams& params, std::uint32_t& rng);
  Status run_guided_cycles(const GraphCutParams& params, std::uint32_t& rng, GraphCutReport& report,
                           std::int64_t& e);
  Status run_full_cycles(const GraphCutParams& params, std::uint32_t& rng, GraphCutReport& report,
                         std::int64_t& e);
  void write_output(Rect roi, DisparityMap& out, GraphCutReport& report) const;
  Result<bool> dp_labels(const StereoInput& in, Rect roi, const GraphCutParams& params);
  void labels_from_map(const ConstDisparityMap& map);
  // Cached terms of the active assignment of pixel p (see keep_).
  void refresh_pixel(int p, int x, int y);
  void refresh_all();
  std::int64_t energy() const;
  // One alpha-expansion; returns the energy change applied (<= 0). With
  // band >= 0 only pixels whose guide_ is negative or within band of alpha
  // may change.
  std::int64_t expand(int alpha, std::int64_t& nodes_used, int band = -1);
  // expand()'s steps (match_graphcut_expansion.cpp: A, R, B, Q, C, the update).
  struct Expansion;
  void alpha_assignments(const Expansion& e, int band);
  void fix_inactive_alphas();
  void old_assignments(const Expansion& e);
  void fix_kept_olds();
  std::int64_t build_graph(const Expansion& e);
  int apply_cut(const Expansion& e, std::int32_t num_nodes);
  void refresh_changed(int changed);

  GraphCutBudget budget_{};
  MaxFlow<6> maxflow_;       // 4 neighbours + 2 uniqueness links per node
  std::span<Sample> left_;   // ROI pixels
  std::span<Sample> right_;  // right strip pixels
  std::span<std::uint8_t> left_flags_;
  std::span<std::uint8_t> right_flags_;
  std::span<std::int16_t> label_;       // per ROI pixel: kOccluded or d - disp_min
  std::span<std::int16_t> cost_;        // D of the active assignment
  std::span<std::int16_t> alpha_cost_;  // D of (p, alpha) for the current expansion
  std::span<std::int32_t> alpha_node_;  // node id, or a code (see expansion)
  std::span<std::int32_t> old_node_;
  std::span<std::int32_t> alpha_slack_;  // reduction bookkeeping (see expansion)
  std::span<std::int32_t> old_slack_;
  std::span<std::int32_t> worklist_;
  std::span<std::uint8_t> alpha_edges_;  // edge bits of (p, alpha) for the current expansion
  std::span<std::int32_t> node_pixel_;   // per graph node: 2 * pixel + (1 if old node)
  // Kept up to date with the labelling (refreshed where labels change):
  // keep_ = D - K of p's active assignment plus the Potts weights towards
  // neighbours that do not share its disparity; old_edges_ = its edge bits.
  std::span<std::int32_t> keep_;
  std::span<std::uint8_t> old_edges_;
  std::span<std::int32_t> right_best_;   // per strip pixel, for the starting labelling
  std::span<std::int16_t> owner_;        // per strip pixel: ROI x of its match, or -1
  std::span<std::int16_t> order_;        // disparity order of a cycle
  std::span<std::int32_t> last_change_;  // change counter at each disparity's last expansion
  std::span<std::int16_t> guide_;        // per ROI pixel: the starting label (guided cycles)
  std::span<std::byte> dp_scratch_;      // the DP start's arena (match_dp_scratch_bytes)

  // The current problem.
  int w_ = 0, h_ = 0;  // ROI size
  int roi_x_ = 0;      // ROI x in the image
  int image_w_ = 0;
  int strip_x0_ = 0, strip_w_ = 0;  // right strip: image columns [x0, x0 + w)
  int disp_min_ = 0, num_disp_ = 0;
  std::int32_t k_ = 0, lambda1_ = 0, lambda2_ = 0;
  std::int32_t clip2_ = 0;  // clip in doubled gray levels
  bool prune_ = true;
};

}  // namespace petra
