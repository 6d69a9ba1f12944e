// The standard scene set tests and benchmarks regenerate: at least 20 fixed
// scenes covering both boundary cases, several sun elevations, every shape
// and both flat-face counts, each of which builds.
#include "sim/scene/scene_set.hpp"

#include <gtest/gtest.h>

#include <set>

#include "sim/scene/scene.hpp"
#include "sim/scene/scene_geometry.hpp"

namespace petra::sim {
namespace {

TEST(SceneSet, CoversTheCasesAndEveryEntryBuilds) {
  const auto set = standard_scene_set();
  ASSERT_GE(set.size(), 20u);
  EXPECT_EQ(static_cast<int>(set.size()), kStandardSetSize);
  std::set<std::uint64_t> seeds;
  std::set<double> suns;
  std::set<int> boundaries, shapes, faces;
  for (const SceneOptions& o : set) {
    seeds.insert(o.seed);
    ASSERT_TRUE(o.sun_elevation_deg && o.boundary && o.shape && o.flat_faces);
    suns.insert(*o.sun_elevation_deg);
    boundaries.insert(static_cast<int>(*o.boundary));
    shapes.insert(static_cast<int>(*o.shape));
    faces.insert(*o.flat_faces);
    auto s = make_scene(o);
    ASSERT_TRUE(s.ok()) << "seed " << o.seed << ": " << s.error().message;
    EXPECT_GE(static_cast<int>(visible_facets(*s).size()), *o.flat_faces);
  }
  EXPECT_EQ(seeds.size(), set.size());
  EXPECT_GE(suns.size(), 3u);
  EXPECT_EQ(boundaries.size(), 2u);
  EXPECT_EQ(shapes.size(), 3u);
  EXPECT_EQ(faces.size(), 2u);
}

}  // namespace
}  // namespace petra::sim
