// The pipeline job the flight build runs. One place to plug the algo/
// pipeline in: until it lands, there is none and EVALUATE fails with
// NO_PIPELINE (an honest answer, never made-up planes).
#pragma once

#include "fsw/pipeline_job.hpp"
#include "hal/clock.hpp"

namespace petra::fsw {

// The job with static storage, or nullptr when this build has no pipeline.
// Built on the first call, reading step times from that call's clock (the
// executive's: give the same one as Dependencies::clock).
PipelineJob* flight_pipeline(const hal::Clock& clock);

}  // namespace petra::fsw
