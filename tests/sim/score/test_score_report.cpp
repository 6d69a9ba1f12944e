// Limits turn scores into pass/fail; the table and the JSON carry the figures.
#include "sim/score/score_report.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "algo/core/json_reader.hpp"

namespace petra::sim {
namespace {

ScoreReport report() {
  ScoreReport r;
  PlaneScore p;
  p.truth_planes = 2;
  p.output_planes = 3;
  p.count_agrees = false;
  FacetScore a;
  a.facet = 0;
  a.plane = 0;
  a.normal_error_deg = 1.5;
  a.centroid_plane_distance_mm = 0.4;
  a.centroid_on_facet = true;
  FacetScore b;
  b.facet = 1;
  b.plane = 2;
  b.normal_error_deg = 7.0;
  b.centroid_plane_distance_mm = 2.5;
  b.centroid_outside_mm = 3.0;
  p.facets = {a, b};
  p.extra_planes = {1};
  r.planes = p;
  r.facet_areas_mm2 = {1500, 900};
  DisparityScore d;
  d.truth_pixels = 1000;
  d.bad1_pct = 4.0;
  d.bad2_pct = 1.0;
  r.disparity = d;
  MaskScore m;
  m.precision = 0.9;
  m.recall = NAN;
  r.shadow = m;
  return r;
}

TEST(ScoreReport, EachExceededLimitIsListed) {
  ScoreLimits l;
  EXPECT_TRUE(limit_failures(report(), l).empty());
  l.max_normal_deg = 5;
  l.max_centroid_mm = 3;
  l.require_on_facet = true;
  l.require_count = true;
  l.max_bad1_pct = 3;
  l.max_bad2_pct = 2;
  l.min_shadow_precision = 0.8;
  l.min_shadow_recall = 0.5;
  const auto f = limit_failures(report(), l);
  // count, facet 1 normal, facet 1 on-facet, bad-1, recall undefined.
  ASSERT_EQ(f.size(), 5u);
  EXPECT_NE(f[0].find("plane count 3, truth 2"), std::string::npos);
  EXPECT_NE(f[1].find("facet 1: normal error 7.00 deg > 5.00"), std::string::npos);
  EXPECT_NE(f[2].find("facet 1: centroid 3.00 mm outside"), std::string::npos);
  EXPECT_NE(f[3].find("bad-1 4.00"), std::string::npos);
  EXPECT_NE(f[4].find("recall n/a"), std::string::npos);
}

TEST(ScoreReport, AnUnmatchedFacetFailsPlaneLimits) {
  ScoreReport r = report();
  r.planes->facets[1].plane = -1;
  ScoreLimits l;
  l.max_normal_deg = 90;
  const auto f = limit_failures(r, l);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_NE(f[0].find("facet 1: no plane matched"), std::string::npos);
}

TEST(ScoreReport, TableAndJsonCarryTheFigures) {
  const std::vector<std::string> failures = {"facet 1: normal error 7.00 deg > 5.00"};
  const std::string text = format_score_text(report(), failures);
  EXPECT_NE(text.find("COUNT DIFFERS"), std::string::npos);
  EXPECT_NE(text.find("7.00"), std::string::npos);
  EXPECT_NE(text.find("extra planes: 1"), std::string::npos);
  EXPECT_NE(text.find("LIMIT EXCEEDED: facet 1"), std::string::npos);
  const std::string js = format_score_json(report(), failures);
  std::vector<json::Token> tokens(4096);
  auto doc = json::Document::parse(js, tokens);
  ASSERT_TRUE(doc.ok()) << doc.error().message << "\n" << js;
  const auto planes = doc->find(0, "planes");
  ASSERT_NE(planes, 0u);
  const auto facets = doc->find(planes, "facets");
  const auto f1 = doc->element(facets, 1);
  EXPECT_DOUBLE_EQ(doc->token(doc->find(f1, "normal_error_deg")).number, 7.0);
  EXPECT_EQ(doc->token(doc->find(doc->find(0, "shadow"), "recall")).type, json::Type::null);
  EXPECT_EQ(doc->token(doc->find(0, "limits_met")).number, 0.0);
  EXPECT_EQ(doc->token(doc->find(0, "failures")).count, 1u);
}

}  // namespace
}  // namespace petra::sim
