// Pipeline::set_params: the parameters change after create, the remap tables
// (rig and budget only) stay, and what cannot run is refused with the
// parameters in force kept.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "algo/chain/pipeline.hpp"
#include "tests/support/test_rig.hpp"

namespace petra {
namespace {

TEST(PipelineParams, SetParamsTakesNoByteAndKeepsTheTables) {
  const StereoRig rig = test::bumblebee_rig(3);
  const PipelineBudget budget;  // 1024 x 768, the rig's
  std::vector<std::byte> block(Pipeline::arena_bytes(budget, PipelineParams{}));
  Arena arena(block);
  auto pipeline = Pipeline::create(rig, budget, PipelineParams{}, arena);
  ASSERT_TRUE(pipeline.ok()) << pipeline.error().message;
  const std::size_t tables_end = arena.mark();

  PipelineParams changed;
  changed.shadow_fraction = 0.2;
  changed.range.search_min_px = 40;
  changed.range.search_max_px = 180;
  ASSERT_TRUE(pipeline->set_params(changed).ok());
  EXPECT_EQ(pipeline->params().shadow_fraction, 0.2);
  EXPECT_EQ(pipeline->params().range.search_max_px, 180);
  EXPECT_EQ(arena.mark(), tables_end);

  PipelineParams invalid = changed;
  invalid.shadow_fraction = 1.5;
  const Status s = pipeline->set_params(invalid);
  EXPECT_EQ(s.code(), Errc::invalid_argument);
  EXPECT_NE(std::strstr(s.error().message, "shadow_fraction"), nullptr) << s.error().message;
  EXPECT_EQ(pipeline->params().shadow_fraction, 0.2);  // those in force kept

  PipelineParams wide = changed;  // its range search needs more than the arena holds
  wide.range.search_min_px = 0;
  wide.range.search_max_px = 2000;
  ASSERT_GT(Pipeline::run_bytes(budget, wide), Pipeline::run_bytes(budget, PipelineParams{}));
  EXPECT_EQ(pipeline->set_params(wide).code(), Errc::capacity_exceeded);
  EXPECT_EQ(pipeline->params().range.search_max_px, 180);

  EXPECT_EQ(Pipeline().set_params(changed).code(), Errc::not_ready);
}

}  // namespace
}  // namespace petra
