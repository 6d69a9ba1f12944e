// The proposal scorer (sim/score/proposal_score) on hand-written truth.json
// and proposals.json: a perfect list gives recall 1 and precision 1, a wrong
// plane lowers precision, a missing face lowers recall, planes that are not
// offered count for neither, --top K scores the best K, and bad input names
// the field.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <string>
#include <vector>

#include "sim/score/proposal_score.hpp"

namespace petra::sim {
namespace {

struct Face {
  Eigen::Vector3d normal, centroid;
  bool grindable, reachable;
  const char* reason;
  const char* reach_reason;
};

std::string vec(const Eigen::Vector3d& v) {
  char b[96];
  std::snprintf(b, sizeof b, "[%.9g,%.9g,%.9g]", v.x(), v.y(), v.z());
  return b;
}

// A 40 x 40 mm square facet about the centroid, in the plane of the normal.
std::string facet_json(const Face& f) {
  const Eigen::Vector3d n = f.normal.normalized(), e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  std::string poly;
  for (const auto& [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
    poly += (poly.empty() ? "" : ",") + vec(f.centroid + 20.0 * (a * e1 + b * e2));
  return "{\"normal\":" + vec(n) + ",\"centroid_mm\":" + vec(f.centroid) + ",\"polygon_mm\":[" +
         poly + "],\"visible_area_mm2\":1600,\"grind_face\":true,\"grindable\":" +
         (f.grindable ? "true" : "false") + ",\"reason\":\"" + f.reason +
         "\",\"reachable\":" + (f.reachable ? "true" : "false") + ",\"reach_reason\":\"" +
         f.reach_reason + "\"}";
}

// Rock 0: A (grindable, reached), B (grindable, out of reach); rock 1: C
// (grindable, reached), D (too small).
const std::vector<std::vector<Face>> kRocks = {
    {{{0, -0.6, 0.8}, {0, 600, 60}, true, true, "grindable", "ok"},
     {{0.8, -0.6, 0}, {40, 600, 30}, true, false, "grindable", "joint_limit"}},
    {{{-0.5, -0.5, 0.7}, {-150, 700, 50}, true, true, "grindable", "ok"},
     {{0, 0, 1}, {-150, 740, 90}, false, true, "too_small", "ok"}}};

std::string truth_json(bool with_rocks = true) {
  std::string rocks;
  for (std::size_t r = 0; r < kRocks.size(); ++r) {
    std::string facets;
    for (const auto& f : kRocks[r]) facets += (facets.empty() ? "" : ",") + facet_json(f);
    rocks += (rocks.empty() ? "" : ",") + std::string("{\"id\":") + std::to_string(r) +
             ",\"roi\":[10,10,100,100],\"click\":[50,50],\"height_mm\":80,\"size_mm\":120,"
             "\"facets\":[" +
             facets + "]}";
  }
  return "{\"roi\":[10,10,100,100],\"planes\":2,\"facets\":[" + facet_json(kRocks[0][0]) + "," +
         facet_json(kRocks[0][1]) +
         "],\"ground\":{\"normal\":[0,0,1],\"d_mm\":0},\"sun_dir\":[0,0,1],\"seed\":1" +
         (with_rocks ? ",\"rocks\":[" + rocks + "]" : std::string()) + "}";
}

struct Plane {
  Eigen::Vector3d normal, centroid;
  const char* verdict = "grindable";
  const char* reach = "ok";
};

std::string proposals_json(const std::vector<std::vector<Plane>>& proposals) {
  std::string items;
  for (std::size_t k = 0; k < proposals.size(); ++k) {
    std::string planes;
    for (const auto& p : proposals[k])
      planes += (planes.empty() ? "" : ",") + std::string("{\"normal\":") +
                vec(p.normal.normalized()) + ",\"centroid_mm\":" + vec(p.centroid) +
                ",\"area_mm2\":900,\"verdict\":\"" + p.verdict + "\",\"reach\":\"" + p.reach +
                "\"}";
    items += (items.empty() ? "" : ",") + std::string("{\"rank\":") + std::to_string(k + 1) +
             ",\"roi\":[0,0,10,10],\"note\":\"ok\",\"planes\":[" + planes + "]}";
  }
  return "{\"proposals\":[" + items + "],\"candidates\":" + std::to_string(proposals.size()) +
         ",\"empty_reason\":\"\"}";
}

Plane on(const Face& f) {
  return {f.normal, f.centroid};
}

ProposalScoreReport score(const std::vector<std::vector<Plane>>& proposals,
                          std::optional<int> top = std::nullopt) {
  auto truth = parse_truth_json(truth_json());
  EXPECT_TRUE(truth) << truth.error().message;
  auto props = parse_proposals_json(proposals_json(proposals));
  EXPECT_TRUE(props) << props.error().message;
  auto rep = score_proposals(*truth, *props, top);
  EXPECT_TRUE(rep) << rep.error().message;
  return *rep;
}

TEST(ProposalScore, PerfectListGivesRecallAndPrecisionOne) {
  const auto rep = score({{on(kRocks[0][0])}, {on(kRocks[1][0])}});
  EXPECT_EQ(rep.targets, 2);
  EXPECT_EQ(rep.facets, 4);
  ASSERT_TRUE(rep.recall && rep.precision);
  EXPECT_DOUBLE_EQ(*rep.recall, 1.0);
  EXPECT_DOUBLE_EQ(*rep.precision, 1.0);
  ASSERT_TRUE(rep.best);
  EXPECT_EQ(rep.best->best.rock, 0);
  EXPECT_EQ(rep.best->best.facet, 0);
  EXPECT_NEAR(rep.best->best.normal_error_deg, 0.0, 1e-5);
  EXPECT_NEAR(rep.best->best.centroid_plane_mm, 0.0, 1e-6);
  EXPECT_EQ(rep.best->best.centroid_outside_mm, 0.0);
}

TEST(ProposalScore, WrongPlaneLowersPrecision) {
  const Face& a = kRocks[0][0];
  // 20 deg off A's normal: matches no facet, but offered.
  const Eigen::Vector3d tilted =
      Eigen::AngleAxisd(20 * M_PI / 180, Eigen::Vector3d::UnitX()) * a.normal.normalized();
  const auto rep = score({{on(a), {tilted, a.centroid}}, {on(kRocks[1][0])}});
  EXPECT_DOUBLE_EQ(*rep.recall, 1.0);
  EXPECT_NEAR(*rep.precision, 2.0 / 3.0, 1e-12);
  // An offered plane on a facet the arm cannot reach is no better.
  const auto unreached = score({{on(a)}, {on(kRocks[1][0])}, {on(kRocks[0][1])}});
  EXPECT_NEAR(*unreached.precision, 2.0 / 3.0, 1e-12);
  // A centroid 12 mm off the facet's plane does not match.
  const auto off = score({{{a.normal, a.centroid + 12.0 * a.normal.normalized()}}});
  EXPECT_DOUBLE_EQ(*off.precision, 0.0);
  EXPECT_FALSE(off.best->best.matches);
}

TEST(ProposalScore, MissingFaceLowersRecall) {
  const auto rep = score({{on(kRocks[0][0])}});
  EXPECT_DOUBLE_EQ(*rep.recall, 0.5);
  EXPECT_DOUBLE_EQ(*rep.precision, 1.0);
  ASSERT_EQ(rep.missed.size(), 1u);
  EXPECT_EQ(rep.missed[0], std::make_pair(1, 0));
}

TEST(ProposalScore, PlanesNotOfferedCountForNeither) {
  Plane refused = on(kRocks[1][0]);
  refused.verdict = "too_rough";
  Plane unreachable = on(kRocks[1][0]);
  unreachable.reach = "beyond_reach";
  const auto rep = score({{on(kRocks[0][0])}, {refused, unreachable}});
  EXPECT_EQ(rep.offered, 1);
  EXPECT_DOUBLE_EQ(*rep.recall, 0.5);
  EXPECT_DOUBLE_EQ(*rep.precision, 1.0);
  // Nothing offered: precision undefined, recall 0.
  const auto none = score({{refused}});
  EXPECT_FALSE(none.precision);
  EXPECT_DOUBLE_EQ(*none.recall, 0.0);
  EXPECT_FALSE(none.best);
}

TEST(ProposalScore, TopKScoresTheBestK) {
  const auto rep = score({{on(kRocks[0][0])}, {on(kRocks[1][0])}}, 1);
  EXPECT_EQ(rep.scored, 1);
  EXPECT_DOUBLE_EQ(*rep.recall, 0.5);
  EXPECT_FALSE(score_proposals(*parse_truth_json(truth_json()),
                               *parse_proposals_json(proposals_json({})), 0));
}

TEST(ProposalScore, BadInputNamesTheField) {
  auto single = parse_truth_json(truth_json(false));
  ASSERT_TRUE(single);
  auto rep = score_proposals(*single, *parse_proposals_json(proposals_json({})), std::nullopt);
  ASSERT_FALSE(rep);
  EXPECT_NE(std::string(rep.error().message).find("rocks"), std::string::npos);
  auto bad = parse_proposals_json(R"({"proposals":[{"rank":1,"planes":[{"normal":[0,0,1],
      "centroid_mm":[0,0,0],"reach":"ok"}]}]})");
  ASSERT_FALSE(bad);
  EXPECT_NE(std::string(bad.error().message).find("proposals[0].planes[0].verdict"),
            std::string::npos)
      << bad.error().message;
  std::string truth = truth_json();
  truth.replace(truth.rfind("\"reach_reason\""), 14, "\"reach_cause\"");
  auto t = parse_truth_json(truth);
  ASSERT_FALSE(t);
  EXPECT_NE(std::string(t.error().message).find("rocks[1].facets[1].reach_reason"),
            std::string::npos)
      << t.error().message;
}

TEST(ProposalScore, ReportsAsTextAndJson) {
  const auto rep = score({{on(kRocks[0][0])}});
  const std::string text = format_proposal_score_text(rep);
  EXPECT_NE(text.find("recall:    0.500 (1 of 2)"), std::string::npos) << text;
  EXPECT_NE(text.find("precision: 1.000 (1 of 1)"), std::string::npos) << text;
  const std::string json = format_proposal_score_json(rep);
  EXPECT_NE(json.find("\"recall\":0.5"), std::string::npos) << json;
  EXPECT_NE(json.find("\"on_facet\":true"), std::string::npos) << json;
}

}  // namespace
}  // namespace petra::sim
