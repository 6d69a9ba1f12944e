#include "fsw/pipeline_factory.hpp"

#include "fsw/flight_pipeline_job.hpp"

namespace petra::fsw {

PipelineJob* flight_pipeline(const hal::Clock& clock) {
  static FlightPipelineJob job(clock);  // static storage: no heap
  return &job;
}

}  // namespace petra::fsw
