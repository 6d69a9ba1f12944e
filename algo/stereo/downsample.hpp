// Box downsampling of a gray image region by an integer factor (mean of each
// factor x factor block, rounded), for coarse-to-fine steps. Integer only.
// Inputs: source view, a region of it (source pixels), factor 1..8; output:
// the destination view, written at (region.x / factor, region.y / factor)
// for region.w / factor x region.h / factor pixels. No heap, no scratch.
#pragma once

#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"

namespace petra {

Status downsample_box(ConstGray8View src, Rect region, int factor, Gray8View dst);

}  // namespace petra
