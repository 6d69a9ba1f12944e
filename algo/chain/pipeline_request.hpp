// What the operator asks of one run of the chain (algo/chain/pipeline), in
// original left image pixels. fsw builds it once from SELECT_ROI and carries
// it unchanged to Pipeline::run (fsw/evaluation_service.cpp).
#pragma once

#include <cstdint>

#include "algo/core/image_view.hpp"
#include "algo/surface/grind_footprint.hpp"

namespace petra {

enum class MatchMethod : std::uint8_t { dp, graph_cut };

struct PipelineRequest {
  Rect roi;
  bool has_click = false;
  int click_u = 0;  // px
  int click_v = 0;  // px
  int planes = 2;   // c
  MatchMethod method = MatchMethod::dp;
  // The arm's reach from its pose now (algo/propose/arm_reach), the
  // caller's for the run: each face's footprint is a disc the tool reaches
  // where the face has one. None: the most level disc, reached or not.
  const DiscReach* reach = nullptr;
};

}  // namespace petra
