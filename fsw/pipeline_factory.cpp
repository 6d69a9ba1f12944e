#include "fsw/pipeline_factory.hpp"

#include "fsw/flight_pipeline_job.hpp"

namespace petra::fsw {

PipelineJob* flight_pipeline() {
  static FlightPipelineJob job;  // static storage: no heap
  return &job;
}

}  // namespace petra::fsw
