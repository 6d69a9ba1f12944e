// The pipeline's memory per stage for a budget, as Markdown table rows: what
// petra-fsw prints at boot for its configuration and what `petra-fsw
// --memory-table` generates into docs/memory.md (a test keeps them equal).
#pragma once

#include <cstddef>

#include "algo/chain/pipeline.hpp"

namespace petra::fsw {

// The header (two lines) and one row per budget, each ending in '\n';
// truncated to `size` like snprintf. `roi_w` x `roi_h`: the ROI the budget
// admits (original px). Returns the characters written (or needed).
int format_memory_header(char* buf, std::size_t size);
int format_memory_row(char* buf, std::size_t size, int roi_w, int roi_h,
                      const petra::PipelineBudget& b, std::size_t cloud_points);

// The generated part of docs/memory.md: the flight job's budgets for ROIs
// from 128 x 96 to 640 x 480 (no rig: rectified = original size), 1024 x 768 images.
int format_memory_doc_table(char* buf, std::size_t size);

}  // namespace petra::fsw
