// Middlebury evaluation on ../shared/data (convention of data/README.md):
// bad-1 = percent of pixels whose disparity is missing or differs from the
// ground truth by more than 1 px, over "all" (known ground truth) and
// "nonocc" (known and visible in the right view: the two ground-truth maps
// cross-check, |GT_R(x - round(GT_L(x))) - GT_L(x)| <= 1; tsukuba has no
// right map, so its nonocc is all). Reported strict (invalid is bad) and
// filled (invalid pixels first filled by eval::fill_invalid_background).
// One more figure puts the output on the terms of the published scanline-DP
// figures, whose official masks are not in the shared data: whole-pixel
// disparities (ours rounded) scored on the pixels the right camera sees, the
// occlusion derived from the left ground truth alone. It is a comparison
// aid, never the project's convention.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "algo/core/result.hpp"
#include "sim/io/image_io.hpp"

namespace petra::eval {

struct MiddleburyScene {
  const char* name;
  const char* dir;  // under the data root
  const char* left;
  const char* right;
  const char* gt_left;
  const char* gt_right;  // nullptr when absent
  int gt_scale;          // disparity = gray / scale
  int disp_max;          // search range 0..disp_max
};

// The eight scenes of shared/data (middlebury/ and middlebury2006/).
std::span<const MiddleburyScene> middlebury_scenes();
// Real-rock pairs with ground truth on the same convention (real-rocks/:
// Rocks1, Middlebury 2006 half size).
std::span<const MiddleburyScene> real_rock_scenes();
// Any of the above by name.
const MiddleburyScene* find_middlebury_scene(const std::string& name);

struct MiddleburyData {
  const MiddleburyScene* scene = nullptr;
  io::GrayImage left;
  io::GrayImage right;
  io::FloatImage gt;                 // px, 0 = unknown
  std::vector<std::uint8_t> known;   // 1 = ground truth known
  std::vector<std::uint8_t> nonocc;  // 1 = known and visible in the right view
  // 1 = known and not hidden in the right view by a pixel to its right
  // (x' > x with x' - GT(x') <= x - GT(x)): from the left map alone, any scene.
  std::vector<std::uint8_t> visible;
};

// `root` is the shared data folder (holding middlebury/ and middlebury2006/).
Result<MiddleburyData> load_middlebury(const MiddleburyScene& scene, const std::string& root);

struct Bad1 {
  double nonocc = 0;
  double all = 0;
};
struct MiddleburyScore {
  Bad1 strict;
  Bad1 filled;
  double invalid_pct = 0;  // of known pixels, before filling
  // Filled bad-1 over `visible`, the output rounded to whole pixels (the
  // published figures' terms; see the comment at the top).
  double filled_whole_visible = 0;
};

// `disparity`: full-size left-view disparity, non-finite = invalid.
Result<MiddleburyScore> score_middlebury(ImageView<const float> disparity,
                                         const MiddleburyData& data);

// Known pixels that no known pixel to their right hides in the right view
// (x' > x with x' - gt(x') <= x - gt(x)); the `visible` mask of load_middlebury.
std::vector<std::uint8_t> visible_in_right_view(const io::FloatImage& gt,
                                                const std::vector<std::uint8_t>& known);

// Default data root for tools and tests run from the project directory.
std::string default_data_root(const char* source_dir);

}  // namespace petra::eval
