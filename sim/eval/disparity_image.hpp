// Ground-side conversions of disparity maps: the matcher's Q4 map of an ROI
// to a full-size float image (the PFM contract: left view, invalid = +inf),
// and the benchmark fill rule shared by `petra stereo --fill`, the Middlebury
// scorer and the peers in the benchmark.
#pragma once

#include "algo/core/disparity.hpp"
#include "sim/io/image_io.hpp"

namespace petra::eval {

// width x height image, +inf outside the map's ROI and at invalid pixels.
io::FloatImage to_float_image(const ConstDisparityMap& map, int width, int height);

// Fill rule of dense benchmark submissions: an invalid (non-finite) pixel of
// `area` takes the smaller (background) of the nearest valid disparities to
// its left and right on the same row within `area`; with only one side, that
// one; with none, it stays invalid.
void fill_invalid_background(ImageView<float> disparity, Rect area);
void fill_invalid_background(ImageView<float> disparity);

}  // namespace petra::eval
