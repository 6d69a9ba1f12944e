// Where each step of the onboard chain (algo/core/pipeline_steps.hpp) is counted
// among the step slots housekeeping and EVAL_RESULT carry (Step,
// PETRA_PIPELINE_STEPS in tlm/tlm_defs.hpp). A switch without a default: the
// compiler names any step added to the chain and not given a slot here.
#pragma once

#include "algo/core/pipeline_steps.hpp"
#include "fsw/pipeline_job.hpp"

namespace petra::fsw {

constexpr Step slot_of(PipelineStep step) {
  switch (step) {
    case PipelineStep::rectify:
      return Step::RECTIFY;
    case PipelineStep::shadow:
      return Step::SHADOW;
    case PipelineStep::disparity_range:    // the coarse match
    case PipelineStep::calibration_check:  // runs on the coarse match's corners
    case PipelineStep::match:
      return Step::MATCH;
    case PipelineStep::mean_filter:
    case PipelineStep::triangulate:
    case PipelineStep::delaunay:
    case PipelineStep::mesh_filter:
      return Step::RECONSTRUCT;
    case PipelineStep::segmentation:
      return Step::SEGMENT;
    case PipelineStep::normals:
    case PipelineStep::grind_planes:
    case PipelineStep::plane_refinement:
      return Step::PLANES;
  }
  return Step::PLANES;  // not reached: every step has its case above
}

}  // namespace petra::fsw
