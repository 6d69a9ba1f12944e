// truth.json and planes.json readers: the contract's fields, and a clear
// message naming the field for every malformed input.
#include <gtest/gtest.h>

#include <string>

#include "sim/score/planes_file.hpp"
#include "sim/score/truth_file.hpp"

namespace petra::sim {
namespace {

const char* kTruth = R"({"roi":[10,20,300,200],"planes":1,
 "facets":[{"normal":[0,0,1],"centroid_mm":[1,1,5],"polygon_mm":[[0,0,5],[2,0,5],[2,2,5],[0,2,5]],
            "visible_area_mm2":4,"grind_face":true},
           {"normal":[1,0,0],"centroid_mm":[2,1,2.5],"polygon_mm":[[2,0,0],[2,2,0],[2,2,5]],"visible_area_mm2":5}],
 "ground":{"normal":[0,0,1],"d_mm":0},"sun_dir":[0,0.6,0.8],"seed":17,"roi_rectified":[12,18,290,210]})";

const char* kPlanes =
    R"({"planes":[{"normal":[0,0,1],"centroid_mm":[1,1,5],"area_mm2":3.5,"rms_mm":0.2,"triangles":12}],
 "ground":{"normal":[0,0,1],"d_mm":-0.5},
 "stats":{"dense_points":100,"filtered_points":90,"disparity_min":120,"disparity_max":180}})";

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  if (p != std::string::npos) s.replace(p, from.size(), to);
  return s;
}

TEST(ScoreFiles, ReadsTheTruthContract) {
  auto t = parse_truth_json(kTruth);
  ASSERT_TRUE(t.ok()) << t.error().message;
  EXPECT_EQ(t->roi, (Rect{10, 20, 300, 200}));
  EXPECT_EQ(t->planes, 1);
  ASSERT_EQ(t->facets.size(), 2u);
  EXPECT_EQ(t->facets[0].polygon_mm.size(), 4u);
  EXPECT_TRUE(t->facets[0].grind_face);
  EXPECT_FALSE(t->facets[1].grind_face);
  EXPECT_DOUBLE_EQ(t->facets[1].visible_area_mm2, 5);
  EXPECT_EQ(t->seed, 17);
  ASSERT_TRUE(t->roi_rectified.has_value());
  EXPECT_EQ(t->roi_rectified->h, 210);
}

TEST(ScoreFiles, ReadsThePlanesContract) {
  auto p = parse_planes_json(kPlanes);
  ASSERT_TRUE(p.ok()) << p.error().message;
  ASSERT_EQ(p->planes.size(), 1u);
  EXPECT_EQ(p->planes[0].triangles, 12);
  EXPECT_DOUBLE_EQ(p->planes[0].rms_mm, 0.2);
  ASSERT_TRUE(p->ground.has_value());
  EXPECT_DOUBLE_EQ(p->ground->d_mm, -0.5);
  // An empty plane list is valid (nothing qualified).
  auto empty = parse_planes_json(R"({"planes":[]})");
  ASSERT_TRUE(empty.ok());
  EXPECT_TRUE(empty->planes.empty());
}

// A unit normal as written (17 digits, as telemetry's f64 reaches planes.json)
// reads back bit for bit; one off unit by more than rounding is normalised.
TEST(ScoreFiles, AUnitNormalReadsBackAsWritten) {
  const Eigen::Vector3d written(-0.022021780540577705, -0.23032458491230268, 0.9728646497672726);
  auto p = parse_planes_json(
      R"({"planes":[{"normal":[-0.022021780540577705,-0.23032458491230268,0.9728646497672726],)"
      R"("centroid_mm":[1,1,5],"area_mm2":3.5,"rms_mm":0.2,"triangles":12}]})");
  ASSERT_TRUE(p.ok()) << p.error().message;
  EXPECT_EQ(p->planes[0].normal, written);
  EXPECT_NE(Eigen::Vector3d(written / written.norm()), written);  // what dividing did
  auto q = parse_planes_json(
      R"({"planes":[{"normal":[0,0.6,0.8004],"centroid_mm":[1,1,5],"area_mm2":3.5,)"
      R"("rms_mm":0.2,"triangles":12}]})");
  ASSERT_TRUE(q.ok()) << q.error().message;
  EXPECT_NEAR(q->planes[0].normal.norm(), 1.0, 1e-15);
}

TEST(ScoreFiles, MalformedTruthNamesTheProblem) {
  const std::string t = kTruth;
  const std::pair<std::string, std::string> cases[] = {
      {"{\"roi\":", "truth.json: json"},                           // not JSON
      {replace(t, "\"planes\":1", "\"planes\":3"), "planes = 3"},  // more than the facets
      {replace(t, "\"planes\":1", "\"planes\":0"), "planes = 0"},
      {replace(t, "\"roi\":[10,20,300,200]", "\"roi\":[10,20,300]"), "roi"},
      {replace(t, "\"roi\":[10,20,300,200]", "\"roi\":[10,20,0,200]"), "roi"},
      {replace(t, "\"normal\":[0,0,1],\"centroid_mm\":[1,1,5]",
               "\"normal\":[0,0,2],\"centroid_mm\":[1,1,5]"),
       "facets[0].normal: length 2"},
      {replace(t, "[[2,0,0],[2,2,0],[2,2,5]]", "[[2,0,0],[2,2,0]]"), "facets[1].polygon_mm"},
      {replace(t, "\"visible_area_mm2\":5", "\"visible_area_mm2\":\"5\""),
       "facets[1].visible_area_mm2"},
      {replace(t, "\"seed\":17,", ""), "seed: missing"},
      {replace(t, "\"sun_dir\":[0,0.6,0.8]", "\"sun_dir\":[0,0.6]"), "sun_dir"},
      {replace(t, "\"d_mm\":0", "\"d_mm\":null"), "ground.d_mm"},
      {"[1,2,3]", "expected a JSON object"},
  };
  for (const auto& [text, expect] : cases) {
    auto r = parse_truth_json(text);
    ASSERT_FALSE(r.ok()) << expect;
    EXPECT_NE(std::string(r.error().message).find(expect), std::string::npos)
        << "got: " << r.error().message << " expected: " << expect;
  }
}

TEST(ScoreFiles, MalformedPlanesNamesTheProblem) {
  const std::string p = kPlanes;
  const std::pair<std::string, std::string> cases[] = {
      {"", "planes.json: json"},
      {"{\"planes\":[{]}", "planes.json: json"},
      {"{}", "planes: missing"},
      {R"({"planes":{}})", "planes: expected an array"},
      {replace(p, "\"normal\":[0,0,1],\"centroid_mm\"", "\"normal\":[0,0,0],\"centroid_mm\""),
       "planes[0].normal: length 0"},
      {replace(p, "\"centroid_mm\":[1,1,5]", "\"centroid_mm\":[1,1]"), "planes[0].centroid_mm"},
      {replace(p, "\"triangles\":12", "\"triangles\":1.5"), "planes[0].triangles"},
      {replace(p, "\"rms_mm\":0.2", "\"rms_mm\":true"), "planes[0].rms_mm"},
      {replace(p, "\"d_mm\":-0.5", "\"dd\":-0.5"), "ground.d_mm: missing"},
  };
  for (const auto& [text, expect] : cases) {
    auto r = parse_planes_json(text);
    ASSERT_FALSE(r.ok()) << expect;
    EXPECT_NE(std::string(r.error().message).find(expect), std::string::npos)
        << "got: " << r.error().message << " expected: " << expect;
  }
}

}  // namespace
}  // namespace petra::sim
