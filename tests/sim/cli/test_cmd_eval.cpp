// `petra eval` as an operator runs it (docs/icd.md, CONTRACTS.md): on a
// rendered scene it exits 0 and writes the five products; every bad argument
// exits non-zero with a one-line reason on stderr naming the problem.
#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "sim/io/image_io.hpp"
#include "sim/scene/scene_render.hpp"
#include "sim/scene/scene_set.hpp"
#include "sim/score/planes_file.hpp"
#include "sim/score/truth_file.hpp"

namespace petra {
namespace {

namespace fs = std::filesystem;

// The petra binary of this build: <build>/sim/petra beside <build>/tests.
std::string petra_binary() {
  std::array<char, 4096> buf{};
  const ssize_t n = readlink("/proc/self/exe", buf.data(), buf.size() - 1);
  if (n <= 0) return "petra";
  return (fs::path(std::string(buf.data(), static_cast<std::size_t>(n)))
              .parent_path()
              .parent_path() /
          "sim" / "petra")
      .string();
}

struct EvalOutcome {
  int status = -1;
  std::string out, err;
};

EvalOutcome run_eval(const std::string& args, const fs::path& dir) {
  const std::string out = (dir / "stdout.txt").string(), err = (dir / "stderr.txt").string();
  const std::string cmd = petra_binary() + " " + args + " > " + out + " 2> " + err;
  EvalOutcome o;
  const int rc = std::system(cmd.c_str());
  o.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  std::ifstream fo(out), fe(err);
  std::stringstream so, se;
  so << fo.rdbuf();
  se << fe.rdbuf();
  o.out = so.str();
  o.err = se.str();
  return o;
}

TEST(CmdEval, ProductsOnASceneAndReasonsForBadArguments) {
  const fs::path dir = fs::temp_directory_path() / ("petra_eval_test_" + std::to_string(getpid()));
  fs::remove_all(dir);
  sim::SceneOptions o = sim::standard_scene_set()[13];  // 2 faces
  o.edge_supersampling = 2;
  auto scene = sim::render_scene(o);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  ASSERT_TRUE(sim::write_scene(*scene, (dir / "scene").string()).ok());
  const auto truth = *sim::parse_truth_json(scene->truth_json);
  const Rect& r = truth.roi;
  const std::string roi = std::to_string(r.x) + "," + std::to_string(r.y) + "," +
                          std::to_string(r.w) + "," + std::to_string(r.h);
  const std::string s = (dir / "scene").string();
  const std::string base = "eval --calib " + s + "/calib.json --left " + s + "/left.png --right " +
                           s + "/right.png --roi " + roi + " --out " + (dir / "out").string();

  EvalOutcome ok = run_eval(base + " --planes " + std::to_string(truth.planes), dir);
  ASSERT_EQ(ok.status, 0) << ok.err;
  EXPECT_NE(ok.out.find("grind planes found"), std::string::npos);
  EXPECT_NE(ok.out.find("dense points"), std::string::npos);
  EXPECT_NE(ok.out.find("timings"), std::string::npos);
  for (const char* f : {"planes.json", "cloud.ply", "mesh.ply", "disparity.png", "overlay.png"})
    EXPECT_TRUE(fs::exists(dir / "out" / f)) << f;
  auto text = io::read_text_file((dir / "out" / "planes.json").string());
  ASSERT_TRUE(text.ok());
  auto planes = sim::parse_planes_json(*text);
  ASSERT_TRUE(planes.ok()) << planes.error().message;
  EXPECT_EQ(static_cast<int>(planes->planes.size()), truth.planes);
  EXPECT_TRUE(io::read_rgb_image((dir / "out" / "overlay.png").string()).ok());
  // The rover's arm, stowed, asked of every plane's footprint (--arm stowed, the default).
  const std::string listed = text->substr(0, text->find("\"ground\""));
  std::size_t asked = 0;
  for (std::size_t at = listed.find("\"reach\":\""); at != std::string::npos;
       at = listed.find("\"reach\":\"", at + 1))
    ++asked;
  EXPECT_EQ(asked, planes->planes.size()) << listed;

  // The truth disparity replayed through the back half (--method gc is run on
  // the scene set by toolchain/eval-scenes.sh and in test_eval_pipeline).
  // With --arm none, no reach is asked.
  EvalOutcome given = run_eval(base + " --planes " + std::to_string(truth.planes) +
                                   " --disparity " + s + "/disparity_truth.pfm --arm none",
                               dir);
  ASSERT_EQ(given.status, 0) << given.err;
  EXPECT_NE(given.out.find("given map"), std::string::npos) << given.out;
  auto given_text = io::read_text_file((dir / "out" / "planes.json").string());
  ASSERT_TRUE(given_text.ok());
  EXPECT_EQ(given_text->find("\"reach\""), std::string::npos);

  // Each refusal: exit 1, one line on stderr naming the problem.
  // Degenerate ROIs (the "bad input"): ground only below the rock,
  // the rock's upper half without ground, and too few pixels to match.
  auto roi_args = [&](int x, int y, int w, int h) {
    return "eval --calib " + s + "/calib.json --left " + s + "/left.png --right " + s +
           "/right.png --planes 2 --out " + (dir / "out").string() + " --roi " + std::to_string(x) +
           "," + std::to_string(y) + "," + std::to_string(w) + "," + std::to_string(h);
  };
  ASSERT_LT(r.y + r.h + 110, 768);
  struct Case {
    std::string args;
    const char* says;
  };
  const Case cases[] = {
      {base + " --planes 9", "--planes 9"},
      {base + " --planes 0", "--planes 0"},
      {base + " --planes 2 --method sgm", "--method sgm"},
      {base + " --planes 2 --arm folded", "--arm folded: expected stowed or none"},
      {base + " --planes 2 --disparity " + s + "/nothing.pfm", "nothing.pfm"},
      {base + " --planes 2 --disparity " + s + "/left.png", "left.png"},
      {base + " --planes 2 --click 1,1", "outside the ROI"},
      {base + " --planes 2 --click 12x4", "point"},
      {roi_args(r.x, r.y + r.h + 10, r.w, 100), "no rock: the points lie on one plane"},
      {roi_args(r.x + r.w / 4, r.y + r.h / 8, r.w / 2, r.h / 2), "no ground in the ROI"},
      {roi_args(r.x, r.y, 3, 2), "coarse matches"},
      {"eval --calib " + s + "/nothing.json --left " + s + "/left.png --right " + s +
           "/right.png --roi " + roi + " --planes 2 --out " + (dir / "out").string(),
       "nothing.json"},
      {"eval --calib " + s + "/calib.json --left " + s + "/left.png --right " + s +
           "/right.png --roi 1000,700,90,90 --planes 2 --out " + (dir / "out").string(),
       "not inside"},
      {"eval --calib " + s + "/calib.json --left " + s + "/left.png --right " + s +
           "/right.png --roi 10,10,ab --planes 2 --out " + (dir / "out").string(),
       "roi"},
  };
  for (const Case& c : cases) {
    EvalOutcome bad = run_eval(c.args, dir);
    EXPECT_EQ(bad.status, 1) << c.args;
    // The reason is the last line; any before it are progress reports.
    ASSERT_FALSE(bad.err.empty()) << c.args;
    const std::size_t start = bad.err.rfind('\n', bad.err.size() - 2);
    const std::string last = bad.err.substr(start == std::string::npos ? 0 : start + 1);
    EXPECT_NE(last.find(c.says), std::string::npos) << c.args << "\n" << bad.err;
    EXPECT_EQ(last.rfind("petra eval: ", 0), 0u) << last;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace petra
