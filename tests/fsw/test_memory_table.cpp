// docs/memory.md's table is what `petra-fsw --memory-table` generates today
// (regenerate and compare, so it cannot drift), and the figures in it add up.
#include "fsw/memory_table.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "fsw/flight_pipeline_job.hpp"

namespace petra::fsw {
namespace {

constexpr const char* kBegin = "<!-- BEGIN generated: petra-fsw --memory-table -->\n";
constexpr const char* kEnd = "<!-- END generated -->";

std::string generated() {
  static char buf[8192];
  const int n = format_memory_doc_table(buf, sizeof(buf));
  EXPECT_LT(n, static_cast<int>(sizeof(buf)));
  return buf;
}

TEST(MemoryTable, DocsMatchTheGenerator) {
  std::ifstream f(std::string(PETRA_SOURCE_DIR) + "/docs/memory.md");
  std::stringstream s;
  s << f.rdbuf();
  const std::string doc = s.str();
  const auto b = doc.find(kBegin), e = doc.find(kEnd);
  ASSERT_NE(b, std::string::npos) << "docs/memory.md has no generated table";
  ASSERT_NE(e, std::string::npos);
  EXPECT_EQ(doc.substr(b + std::string(kBegin).size(), e - b - std::string(kBegin).size()),
            generated())
      << "docs/memory.md is out of date: paste `petra-fsw --memory-table` between the markers";
}

TEST(MemoryTable, StagesAddUpToTheArenaAndGrowWithTheRoi) {
  std::size_t last = 0;
  for (int w : {128, 256, 512}) {
    JobBudget eb;
    eb.max_width = 1024;
    eb.max_height = 768;
    eb.max_roi_width = w;
    eb.max_roi_height = w * 3 / 4;
    const FlightPipelineJob::Sizing s = FlightPipelineJob::sizing(eb);
    const PipelineMemory m = Pipeline::memory(
        s.pipeline, FlightPipelineJob::pipeline_params(FlightPipelineJob::default_settings()));
    EXPECT_EQ(m.total(),
              Pipeline::arena_bytes(s.pipeline, FlightPipelineJob::pipeline_params(
                                                    FlightPipelineJob::default_settings())));
    EXPECT_EQ(m.largest_step(), std::max({m.range, m.calib_check, m.match_dp, m.match_graph_cut,
                                          m.reconstruction + m.refinement}));
    EXPECT_GT(m.match_graph_cut, 0u);  // the flight job keeps room for MATCH_METHOD 1
    EXPECT_GT(m.total(), last);
    last = m.total();
  }
}

}  // namespace
}  // namespace petra::fsw
