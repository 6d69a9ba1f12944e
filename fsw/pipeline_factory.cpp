#include "fsw/pipeline_factory.hpp"

namespace petra::fsw {

PipelineJob* flight_pipeline() {
  return nullptr;
}

}  // namespace petra::fsw
