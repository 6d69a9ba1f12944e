// A rendered multi-rock scene (seed 7, 3 rocks, clean world: about 4 s of
// one core, made once per build tree) read back the way `petra score
// proposals` reads it: truth.json's rocks round-trip, rock 0's entry is the
// top-level truth, each rock's click sees that rock in the rendered truth,
// and proposals on exactly the grindable, reachable facets score recall 1
// and precision 1 while one on a non-target facet lowers precision.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "sim/io/image_io.hpp"
#include "sim/scene/camera_rays.hpp"
#include "sim/scene/ray_cast.hpp"
#include "sim/scene/scene_render.hpp"
#include "sim/score/proposal_score.hpp"
#include "tests/support/multirock_scene.hpp"

namespace petra::sim {
namespace {

namespace fs = std::filesystem;

SceneOptions options() {
  return test::multirock_options();
}

const fs::path& scene_dir() {
  return test::multirock_scene_dir();
}

TruthFile truth() {
  auto text = io::read_text_file((scene_dir() / "truth.json").string());
  EXPECT_TRUE(text);
  auto t = parse_truth_json(text ? *text : std::string("{}"));
  EXPECT_TRUE(t) << t.error().message;
  return t ? std::move(*t) : TruthFile{};
}

TEST(SceneRocksRendered, RockZeroIsTheTopLevelTruth) {
  const TruthFile t = truth();
  ASSERT_EQ(t.rocks.size(), 3u);
  const TruthRock& r0 = t.rocks[0];
  EXPECT_EQ(r0.roi.x, t.roi.x);
  EXPECT_EQ(r0.roi.w, t.roi.w);
  ASSERT_EQ(r0.facets.size(), t.facets.size());
  for (std::size_t k = 0; k < t.facets.size(); ++k) {
    EXPECT_EQ(r0.facets[k].normal, t.facets[k].normal);
    EXPECT_EQ(r0.facets[k].centroid_mm, t.facets[k].centroid_mm);
    EXPECT_EQ(r0.facets[k].grind_face, t.facets[k].grind_face);
  }
  for (std::size_t r = 0; r < t.rocks.size(); ++r) EXPECT_EQ(t.rocks[r].id, static_cast<int>(r));
}

TEST(SceneRocksRendered, EachClickSeesItsRock) {
  const TruthFile t = truth();
  auto scene = make_scene(options());
  ASSERT_TRUE(scene);
  ASSERT_EQ(rock_count(*scene), static_cast<int>(t.rocks.size()));
  const CameraRays rays(scene->rig.left);
  for (std::size_t r = 0; r < t.rocks.size(); ++r) {
    ASSERT_TRUE(t.rocks[r].click) << "rock " << r;
    const Eigen::Vector2i c = *t.rocks[r].click;
    const Rect& roi = t.rocks[r].roi;
    EXPECT_TRUE(c.x() >= roi.x && c.x() < roi.x + roi.w && c.y() >= roi.y && c.y() < roi.y + roi.h);
    const SceneHit hit = trace(*scene, rays.origin(), rays.direction(c.x(), c.y()));
    EXPECT_GE(face_of_rock(hit.surface, static_cast<int>(r)), 0) << "rock " << r;
  }
}

// One proposal per rock, each offering a plane on every facet `pick` chooses.
template <class Pick>
ProposalsFile proposals_on(const TruthFile& t, Pick pick) {
  ProposalsFile out;
  for (const auto& rock : t.rocks) {
    Proposal p;
    p.rank = static_cast<int>(out.proposals.size()) + 1;
    for (const auto& f : rock.facets)
      if (pick(f)) p.planes.push_back({f.normal, f.centroid_mm, 0, "grindable", "ok"});
    out.proposals.push_back(p);
  }
  return out;
}

TEST(SceneRocksRendered, ProposalsOnTheTargetsScoreOne) {
  const TruthFile t = truth();
  auto perfect = score_proposals(
      t, proposals_on(t, [](const TruthFacet& f) { return f.grindable && f.reachable; }),
      std::nullopt);
  ASSERT_TRUE(perfect) << perfect.error().message;
  EXPECT_GT(perfect->targets, 0);
  ASSERT_TRUE(perfect->recall && perfect->precision);
  EXPECT_DOUBLE_EQ(*perfect->recall, 1.0);
  EXPECT_DOUBLE_EQ(*perfect->precision, 1.0);
  // Offering the too-small rock's faces as well lowers precision only.
  auto more =
      score_proposals(t,
                      proposals_on(t,
                                   [](const TruthFacet& f) {
                                     return (f.grindable && f.reachable) || f.reason == "too_small";
                                   }),
                      std::nullopt);
  ASSERT_TRUE(more);
  EXPECT_DOUBLE_EQ(*more->recall, 1.0);
  EXPECT_LT(*more->precision, 1.0);
}

}  // namespace
}  // namespace petra::sim
