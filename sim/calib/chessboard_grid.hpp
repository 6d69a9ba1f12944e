// Grid topology from X-corner candidates. Two corners are linked when each
// lies along one of the other's edge lines, nothing nearer lies in that
// direction, and the segment between them separates a dark square from a
// bright one along its whole length (which rules out links that skip a
// missed corner). From a seed with four links, grid coordinates spread over
// the links: crossing a link keeps the axis, and the perpendicular axis keeps
// the seed's handedness (perspective preserves orientation).
// Output: the largest consistently labelled component as a dense array of
// cells (-1 where a corner is missing inside the extent).
#pragma once

#include <vector>

#include "algo/core/image_view.hpp"
#include "sim/calib/xcorner_candidates.hpp"

namespace petra::calib {

struct GridLabelling {
  int width = 0;          // extent along the grid's first axis
  int height = 0;         // extent along the second
  std::vector<int> cell;  // index into the corners, i + j*width; -1 where missing
  int conflicts = 0;      // links that disagreed with the labelling (ignored)

  int at(int i, int j) const { return cell[static_cast<std::size_t>(j) * width + i]; }
  int found() const;
};

GridLabelling label_grid(const std::vector<XCorner>& corners, ImageView<const float> smooth,
                         double min_contrast);

// True when the segment a-b has a dark side and a bright side along its
// length (samples at 30, 50, 70 % of it, a quarter of its length off either side).
bool separates_squares(ImageView<const float> smooth, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b, double min_contrast);

}  // namespace petra::calib
