// Sub-pixel refinement of a chessboard (saddle) corner by gradient
// orthogonality (Foerstner 1987; the principle OpenCV's cornerSubPix uses):
// around the true corner c, every image gradient g(q) is orthogonal to q - c,
// so c solves sum w g g^T c = sum w g g^T q over a window. Iterated on a
// bilinearly resampled window centred on the current estimate, with Gaussian
// weights exp(-(dx/h)^2 - (dy/h)^2) for half-window h.
// Input: float image (unsmoothed), a start within about h px of the corner.
// Output: the corner in pixels, or an error when the window leaves the image,
// the gradients have no corner structure, or the estimate runs away.
#pragma once

#include <Eigen/Core>

#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"

namespace petra::calib {

struct SubpixOptions {
  int half_window = 5;  // window side 2h+1 px
  int max_iterations = 40;
  double epsilon_px = 0.002;  // stop when an update moves less than this
};

Result<Eigen::Vector2d> refine_corner(ImageView<const float> image, const Eigen::Vector2d& start,
                                      const SubpixOptions& options = {});

}  // namespace petra::calib
