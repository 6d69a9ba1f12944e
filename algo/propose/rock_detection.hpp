// Rocks over a whole stereo pair (issue 26, step 1; docs/proposals.md):
//   rectify the whole pair (the chain's rectifier) -> box-downsample both by
//   `factor` (algo/stereo/downsample) -> scanline-DP match of the region at
//   that resolution over the rig's envelope / factor (algo/stereo/match_dp)
//   -> triangulate every matched pixel (algo/mesh/triangulate, eq. 8)
//   -> the ground over the field of view: the chain's robust fit
//   (algo/surface/ground_segment: MSAC seed on the border band, k-means and
//   least-squares refit, depth-noise tolerance at this resolution's
//   disparity noise) and its normals check (algo/surface/ground_normals, on
//   normals from the point grid's neighbours)
//   -> rocks: 8-connected regions of the grid whose points stand more than
//   max(min_band_mm, band_rms x ground RMS, band_sigmas x sigma_Z(range))
//   above the ground and lie within max_range_mm of the left camera, split
//   where two height maxima meet at a saddle (touching or close rocks: each
//   part's peak split_prominence_mm above the saddle and min_pixels large),
//   each part kept when its highest
//   interior point (all 8 neighbours in the region: never the silhouette's mismatched fringe) is
//   min_height_mm above the ground, its largest horizontal extent is at
//   least min_size_mm and it holds min_pixels.
// Each rock: its ROI in original left pixels (the interior's box padded so
// the chain sees ground all round), a click (the interior point nearest the
// box's centre: on the rock, never its outline), height and size.
// Memory: the caller's arena, sized by detection_arena_bytes(budget), all
// released on return; outputs are values. No heap, no I/O.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/camera/rectify.hpp"
#include "algo/core/arena.hpp"
#include "algo/core/chain_defaults.hpp"
#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"
#include "algo/core/step_clock.hpp"
#include "algo/propose/proposals.hpp"
#include "algo/stereo/match_dp.hpp"
#include "algo/surface/ground_normals.hpp"
#include "algo/surface/ground_segment.hpp"

namespace petra {

// Rocks one detection keeps (the largest first).
inline constexpr int kMaxRockCandidates = 16;

// Sizes fixed at init.
struct DetectionBudget {
  int image_width = 1024;  // px, calib.json's
  int image_height = 768;
  int factor = 4;                      // downsampling of the pair, 1..8
  int search_min_px = kEnvelopeMinPx;  // full-resolution disparity envelope
  int search_max_px = kEnvelopeMaxPx;
};
Status validate(const DetectionBudget& b);

struct DetectionParams {
  MatchDpParams match;  // disp_min/max set from the budget's envelope / factor
  // The chain's ground fit; the rock checks are detection's own (below): over
  // the whole view rocks are a small share and a view may hold none.
  GroundParams ground = [] {
    GroundParams g;
    g.min_rock_height_mm = 0.5;  // must be > 0; the band (min_band_mm) decides
    g.min_rock_height_rms = 0;
    return g;
  }();
  GroundNormalParams ground_normals;
  double band_rms = 3.0;     // a rock point: this many ground RMS above the plane ...
  double min_band_mm = 4.0;  // ... and at least this far
  double band_sigmas = 3.0;  // ... and this many of the point's own depth noise sigma_Z
  // Rock points no farther than this from the left camera: the arm reaches
  // about 0.8 m from its base beside the cameras (docs/arm.md); beyond, the
  // 1/4 resolution's depth noise passes the far field's relief for rocks.
  double max_range_mm = 1500.0;
  double min_height_mm = 8.0;  // a rock's highest point above the ground
  double min_size_mm = 20.0;   // its largest horizontal extent (the grinder's disc)
  long min_pixels = 12;        // at the detection's resolution
  // A region holding several rocks is split where two height maxima meet:
  // both parts' peaks stand this far above the saddle between them (and
  // both hold min_pixels), else the lower part joins the higher.
  double split_prominence_mm = 12.0;
  double pad = 0.5;     // ROI margin each side, times the rock's larger box side
  int min_pad_px = 24;  // ... at least this many original pixels
};
Status validate(const DetectionParams& p);

struct DetectionResult {
  RockCandidate rocks[kMaxRockCandidates];  // largest (pixels) first
  int count = 0;
  int regions = 0;  // connected regions above the band, before the size checks
  GroundResultT<double> ground;
  long points = 0;     // triangulated points at the detection's resolution
  Rect region_coarse;  // the matched region, downsampled rectified pixels
  MatchDpStats match;
};

std::size_t detection_arena_bytes(const DetectionBudget& b);

// The rock map detection can fill: per cell of step x step grid pixels (the
// grid at 1 / factor; step the least that fits the grid in
// kRockMapMaxWidth x kRockMapMaxHeight cells: 2 for 1024 x 768 at 1/4, a
// cell of 8 original px) the index in rocks[] of the rock a point of it
// belongs to, kOtherRock for a region standing out that is not a candidate
// (too small, too low, past the 16 largest), kNoRock for the ground or no
// point. Small and fixed: the proposer keeps it through the chain runs
// outside the arena.
inline constexpr int kRockMapMaxWidth = 128;
inline constexpr int kRockMapMaxHeight = 96;
struct RockMapShape {
  int w = 0, h = 0, step = 1;
  std::size_t cells() const { return static_cast<std::size_t>(w) * static_cast<std::size_t>(h); }
};
RockMapShape rock_map_shape(const DetectionBudget& b);
inline constexpr std::uint8_t kOtherRock = 0xFE;
inline constexpr std::uint8_t kNoRock = 0xFF;
static_assert(kMaxRockCandidates < kOtherRock);

// Detects the rocks in `region` (original left pixels; empty: the whole
// image). Errors: images not the rectifier's size, a region outside the
// image, no ground over the field of view (named), cancelled, arena short.
// `rock_map` (empty, or rock_map_shape(b).cells() long): filled as said above.
Result<DetectionResult> detect_rocks(const Rectifier& rectifier, ConstGray8View left,
                                     ConstGray8View right, Rect region, const DetectionBudget& b,
                                     const DetectionParams& p, Arena& arena, const StepClock& clock,
                                     std::span<std::uint8_t> rock_map = {});

// The back half on a given map at 1 / factor resolution (downsampled
// rectified left pixels, inside the grid): from triangulation on. A
// truth, a recorded or another matcher's map.
Result<DetectionResult> detect_rocks_in_disparity(const Rectifier& rectifier,
                                                  ConstDisparityMap disparity,
                                                  const DetectionBudget& b,
                                                  const DetectionParams& p, Arena& arena,
                                                  std::span<std::uint8_t> rock_map = {});

}  // namespace petra
