// `petra sim scene` and `petra score` from the command line: files written,
// exit status 0 / 1 (bad input, one line on stderr) / 2 (a limit exceeded).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "sim/score/truth_file.hpp"

namespace {

namespace fs = std::filesystem;

// The petra executable built beside this test (build/<preset>/sim/petra).
fs::path petra() {
  return fs::read_symlink("/proc/self/exe").parent_path().parent_path() / "sim" / "petra";
}

// Per process: ctest runs the tests of this file in parallel processes.
fs::path tmp(const std::string& name) {
  return fs::temp_directory_path() / ("petra_cli_" + std::to_string(getpid()) + "_" + name);
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

struct CliResult {
  int status;
  std::string out, err;
};

CliResult run_petra(const std::string& args) {
  const fs::path out = tmp("stdout"), err = tmp("stderr");
  const std::string cmd =
      petra().string() + " " + args + " >" + out.string() + " 2>" + err.string();
  const int raw = std::system(cmd.c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(out), slurp(err)};
}

class PetraCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ASSERT_TRUE(fs::exists(petra())) << petra() << " not built";
    scene_ = tmp("scene");
    fs::remove_all(scene_);
    // Plain surfaces render quicker; these tests are about files and exit codes.
    const CliResult r = run_petra("sim scene --seed 7 --no-texture --out " + scene_.string());
    ASSERT_EQ(r.status, 0) << r.err;
  }
  static fs::path scene_;
};
fs::path PetraCli::scene_;

TEST_F(PetraCli, SceneWritesEveryFile) {
  for (const char* f : {"left.pgm", "right.pgm", "left.png", "right.png", "calib.json",
                        "truth.json", "disparity_truth.pfm", "shadow_truth.pgm"})
    EXPECT_TRUE(fs::exists(scene_ / f)) << f;
  const CliResult r = run_petra("info --calib " + (scene_ / "calib.json").string());
  EXPECT_EQ(r.status, 0) << r.err;
}

TEST_F(PetraCli, BadSceneArgumentsFailWithAReason) {
  const std::string out = " --out " + tmp("bad").string();
  const std::pair<std::string, std::string> cases[] = {
      {"sim scene --seed -1" + out, "--seed -1"},
      {"sim scene --seed 9007199254740993" + out, "--seed"},
      {"sim scene --seed 3 --boundary fuzzy" + out, "boundary"},
      {"sim scene --seed 3 --shape cube" + out, "shape"},
      {"sim scene --seed 3 --sun-elevation 95" + out, "sun-elevation"},
      {"sim scene --seed 3 --flat-faces 5" + out, "flat-faces"},
      {"sim scene --seed 3 --rock-size 20" + out, "rock-size"},
      {"sim scene --set-index 99" + out, "--set-index 99"},
      {"sim scene" + out, "--seed N or --set-index K"},
      {"sim scene --seed 3 --out /proc/petra_cannot_write", "cannot create directory"},
      {"sim scene --seed 3 --out " + (scene_ / "truth.json").string(), "not a directory"},
  };
  for (const auto& [args, expect] : cases) {
    const CliResult r = run_petra(args);
    EXPECT_EQ(r.status, 1) << args;
    EXPECT_NE(r.err.find(expect), std::string::npos) << args << " -> " << r.err;
  }
  EXPECT_NE(run_petra("sim scene --seed abc" + out).status, 0);
}

TEST_F(PetraCli, ScoreExitStatusFollowsTheLimits) {
  const std::string truth_path = (scene_ / "truth.json").string();
  auto truth = petra::sim::parse_truth_json(slurp(truth_path));
  ASSERT_TRUE(truth.ok());
  // A planes.json that is the truth itself, then one with a flipped normal.
  auto planes = [&](bool flip) {
    std::string s = "{\"planes\":[";
    for (int i = 0; i < truth->planes; ++i) {
      const auto& f = truth->facets[static_cast<std::size_t>(i)];
      const double k = flip && i == 0 ? -1 : 1;
      char buf[256];
      std::snprintf(buf, sizeof buf,
                    "%s{\"normal\":[%.17g,%.17g,%.17g],\"centroid_mm\":[%.17g,%.17g,%.17g]}",
                    i ? "," : "", k * f.normal.x(), k * f.normal.y(), k * f.normal.z(),
                    f.centroid_mm.x(), f.centroid_mm.y(), f.centroid_mm.z());
      s += buf;
    }
    return s + "]}";
  };
  const fs::path good = tmp("good.json"), bad = tmp("flipped.json"), broken = tmp("broken.json");
  std::ofstream(good) << planes(false);
  std::ofstream(bad) << planes(true);
  std::ofstream(broken) << "{\"planes\":[{\"normal\":[0,0,1]}]}";
  const std::string limits =
      " --max-normal-deg 2 --max-centroid-mm 1 --require-on-facet --require-count";
  CliResult r = run_petra("score --truth " + truth_path + " --planes " + good.string() + limits);
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("count agrees"), std::string::npos) << r.out;
  r = run_petra("score --truth " + truth_path + " --planes " + bad.string() + limits);
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("facet 0: normal error 180.00"), std::string::npos) << r.err;
  r = run_petra("score --truth " + truth_path + " --planes " + bad.string() + " --json");
  EXPECT_EQ(r.status, 0);  // no limits given
  EXPECT_NE(r.out.find("\"normal_error_deg\":180"), std::string::npos) << r.out;
  r = run_petra("score --truth " + truth_path + " --planes " + broken.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("planes[0].centroid_mm: missing"), std::string::npos) << r.err;
  r = run_petra("score --truth " + good.string() + " --planes " + good.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("roi: missing"), std::string::npos) << r.err;
  r = run_petra("score --truth " + tmp("missing.json").string() + " --planes " + good.string());
  EXPECT_EQ(r.status, 1);
  r = run_petra("score --truth " + truth_path);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("nothing to score"), std::string::npos) << r.err;
  r = run_petra("score --planes " + good.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--planes needs --truth"), std::string::npos) << r.err;
}

// `petra score proposals` (tests/sim/score/test_proposal_score.cpp scores;
// here the command line): a single-rock truth is refused by name, the
// proposals file is required, a malformed one names its field.
TEST_F(PetraCli, ScoreProposalsRefusesBadInputByName) {
  const std::string truth = (scene_ / "truth.json").string();
  const fs::path props = tmp("proposals.json");
  std::ofstream(props) << R"({"proposals":[{"rank":1,"planes":[{"normal":[0,0,1],)"
                       << R"("centroid_mm":[0,0,0],"verdict":"grindable"}]}]})";
  CliResult r = run_petra("score proposals --truth " + truth + " --proposals " + props.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find(truth + ": rocks: missing"), std::string::npos) << r.err;
  r = run_petra("score proposals --truth " + truth);
  EXPECT_EQ(r.status, 2);  // does not parse (docs/ops.md)
  EXPECT_NE(r.err.find("--proposals is required"), std::string::npos) << r.err;
  r = run_petra("score proposals --truth " + truth + " --proposals " + props.string() + " --top 0");
  EXPECT_NE(r.status, 0);
}

TEST_F(PetraCli, ScoresDisparityAndShadowMaps) {
  const std::string d = (scene_ / "disparity_truth.pfm").string();
  const std::string s = (scene_ / "shadow_truth.pgm").string();
  const std::string t = (scene_ / "truth.json").string();
  CliResult r =
      run_petra("score --truth " + t + " --disparity " + d + " --disparity-truth " + d +
                " --shadow " + s + " --shadow-truth " + s + " --max-bad1 0 --min-shadow-recall 1");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("bad-1 0.00 %"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("recall 1.000"), std::string::npos) << r.out;
  // The right camera's mask scored against the left truth fails a recall limit.
  r = run_petra("score --shadow " + (scene_ / "shadow_truth_right.pgm").string() +
                " --shadow-truth " + s + " --shadow-roi 0,0,1024,768 --min-shadow-recall 0.99");
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  r = run_petra("score --disparity " + d + " --disparity-truth " + d +
                " --disparity-roi 1000,700,100,100");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("region"), std::string::npos) << r.err;
  r = run_petra("score --disparity " + d + " --disparity-truth " + s);
  EXPECT_EQ(r.status, 1);
  r = run_petra("score --shadow " + s + " --shadow-truth " + s + " --shadow-roi 1,2,3");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("x,y,w,h"), std::string::npos) << r.err;
}

}  // namespace
