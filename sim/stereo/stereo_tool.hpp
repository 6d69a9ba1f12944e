// The work behind `petra stereo` (docs/icd.md), as a library function so
// tests can drive it: read the pair, rectify with calib.json if given, shadow
// masks for a prior fraction p, run the DP or graph-cut matcher with a budget
// sized for the problem, optionally fill, write the PFM. Every failure is an Error
// naming the input at fault; nothing is written then.
#pragma once

#include <string>

#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"
#include "algo/stereo/match_dp.hpp"
#include "algo/stereo/match_graphcut.hpp"

namespace petra::stereo {

struct StereoToolOptions {
  std::string left, right;  // PGM, PPM or PNG; colour becomes gray
  std::string method = "dp";
  int disp_min = 0;
  int disp_max = 0;
  int gc_band_rows = 0;  // --method gc: bands of this many rows (+16 above and below); 0: whole
  std::string roi;       // "x,y,w,h" in the original left image; empty = whole image
  std::string calib;     // calib.json; empty = the pair is already rectified
  double shadow_fraction = 0.0;
  bool fill = false;
  bool edge_constraint = true;
  std::string out;         // disparity PFM
  std::string confidence;  // optional PNG
};

struct StereoToolReport {
  Rect roi;              // in the matched (rectified) frame
  MatchDpStats stats;    // --method dp
  GraphCutReport graph;  // --method gc
  long matched = 0;      // pixels of the ROI with a disparity
  double match_ms = 0;
};

Result<StereoToolReport> run_stereo_tool(const StereoToolOptions& options);

}  // namespace petra::stereo
