// proposals.png (`petra propose`, docs/proposals.md): the left image with each
// proposal's ROI (in its best plane's colour when offered, grey when not),
// its rank, its click as a cross, and its best plane's centroid with a stroke
// along the normal, projected into the original left image.
#pragma once

#include "algo/camera/camera_model.hpp"
#include "algo/propose/proposals.hpp"
#include "sim/io/image_io.hpp"

namespace petra::eval {

io::RgbImage proposals_picture(ConstGray8View left, const TsaiCamera& camera,
                               const ProposalList& list);

}  // namespace petra::eval
