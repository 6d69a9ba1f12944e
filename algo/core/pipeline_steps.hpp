// The onboard chain's timed steps (algo/chain/pipeline, algo/chain/reconstruction), one
// table: the enum the timers carry and the name printed for each. fsw maps
// each step to its telemetry slot with a switch the compiler checks is total
// (fsw/step_slots.hpp), so a new step cannot be counted in the wrong slot.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iterator>

namespace petra {

// X(id, "name"), in the order the steps run.
#define PETRA_CHAIN_STEPS(X)                \
  X(rectify, "rectify")                     \
  X(disparity_range, "disparity range")     \
  X(calibration_check, "calibration check") \
  X(shadow, "shadow")                       \
  X(match, "match")                         \
  X(mean_filter, "mean filter")             \
  X(triangulate, "triangulate")             \
  X(delaunay, "delaunay")                   \
  X(mesh_filter, "mesh filter")             \
  X(normals, "normals")                     \
  X(segmentation, "segmentation")           \
  X(grind_planes, "grind planes")           \
  X(plane_refinement, "plane refinement")

enum class PipelineStep : std::uint8_t {
#define PETRA_CHAIN_STEP_ENUM(id, name) id,
  PETRA_CHAIN_STEPS(PETRA_CHAIN_STEP_ENUM)
#undef PETRA_CHAIN_STEP_ENUM
};

inline constexpr const char* kPipelineStepNames[] = {
#define PETRA_CHAIN_STEP_NAME(id, name) name,
    PETRA_CHAIN_STEPS(PETRA_CHAIN_STEP_NAME)
#undef PETRA_CHAIN_STEP_NAME
};
inline constexpr std::size_t kPipelineStepCount = std::size(kPipelineStepNames);

constexpr const char* step_name(PipelineStep step) {
  return kPipelineStepNames[static_cast<std::size_t>(step)];
}

}  // namespace petra
