#include "fsw/memory_table.hpp"

#include <cstdio>

#include "algo/mesh/delaunay.hpp"
#include "fsw/config.hpp"
#include "fsw/flight_pipeline_job.hpp"

namespace petra::fsw {

namespace {

double mib(std::size_t bytes) {
  return static_cast<double>(bytes) / 1048576.0;
}

}  // namespace

int format_memory_header(char* buf, std::size_t size) {
  return std::snprintf(
      buf, size,
      "| ROI (px) | rectified (px) | disparities | points | triangles | remap tables | rectified "
      "pair | masks + disparity | range search | calibration check | DP | graph cut | "
      "reconstruction | refinement | "
      "products | arena (MiB) |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
}

int format_memory_row(char* buf, std::size_t size, int roi_w, int roi_h,
                      const petra::PipelineBudget& b, std::size_t cloud_points) {
  const PipelineMemory m = Pipeline::memory(
      b, FlightPipelineJob::pipeline_params(FlightPipelineJob::default_settings()));
  const std::size_t points = points_of(b);
  const std::size_t arena = FlightPipelineJob::need_bytes(b, cloud_points);
  const std::size_t products = arena - m.total();
  return std::snprintf(
      buf, size,
      "| %d x %d | %d x %d | %d | %zu | %zu | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | "
      "%.2f | %.2f | %.2f | %.2f | **%.2f** |\n",
      roi_w, roi_h, b.max_roi_width, b.max_roi_height, b.max_disparities, points,
      delaunay_max_triangles(points), mib(m.tables), mib(m.rectified), mib(m.masks_disparity),
      mib(m.range), mib(m.calib_check), mib(m.match_dp), mib(m.match_graph_cut),
      mib(m.reconstruction), mib(m.refinement), mib(products), mib(arena));
}

int format_memory_doc_table(char* buf, std::size_t size) {
  static constexpr int kRois[][2] = {{128, 96},  {256, 192}, {320, 240}, {384, 288},
                                     {448, 336}, {512, 384}, {640, 480}};
  int n = format_memory_header(buf, size);
  for (const auto& r : kRois) {
    fsw::JobBudget eb;
    eb.max_width = 1024;
    eb.max_height = 768;
    eb.max_cloud_points = Budget{}.cloud_points;
    eb.max_roi_width = r[0];
    eb.max_roi_height = r[1];
    const FlightPipelineJob::Sizing s = FlightPipelineJob::sizing(eb);
    const std::size_t at = static_cast<std::size_t>(n) < size ? static_cast<std::size_t>(n) : size;
    n += format_memory_row(buf + at, size - at, s.roi_width, s.roi_height, s.pipeline,
                           eb.max_cloud_points);
  }
  return n;
}

}  // namespace petra::fsw
