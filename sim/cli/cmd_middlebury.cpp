// `petra middlebury`: scores the onboard matcher on the Middlebury scenes of
// the shared data (convention of sim/eval/middlebury.hpp) and prints the
// bad-1 table, strict and filled; the last column, whole-vis, scores the
// output on the terms of the published scanline-DP figures (whole pixels,
// occluded pixels left out; sim/eval/middlebury.hpp); gray-map the right
// view's gray-level map the matcher applied (gain / level of 0). The benchmark
// tests/bench/bench_stereo.cpp adds the OpenCV peers and timing. Rocks1
// (real-rocks/, same convention) follows the eight Middlebury scenes.
// --perturb changes the right view's gain, offset, noise and vignetting
// reproducibly (sim/eval/middlebury_perturb.hpp) before matching.
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "sim/cli/commands.hpp"
#include "sim/eval/middlebury.hpp"
#include "sim/eval/middlebury_perturb.hpp"
#include "sim/eval/run_match_dp.hpp"

namespace petra::cli {

namespace {

struct MiddleburyOptions {
  std::string data = "../shared/data";  // run from the project directory
  std::string scene;
  bool no_edges = false;
  bool normalise = true;  // the matcher's default
  std::string perturb;    // "gain,offset,sigma[,seed[,vignetting]]"
};

int run(const MiddleburyOptions& o) {
  eval::Perturbation perturbation;
  if (!o.perturb.empty()) {
    auto parsed = eval::parse_perturbation(o.perturb);
    if (!parsed) return fail("middlebury", parsed.error().message);
    perturbation = *parsed;
  }
  std::printf("%-9s %9s %9s %9s %9s %8s %8s %8s %9s %13s\n", "scene", "strict-no", "strict-al",
              "filled-no", "filled-al", "invalid%", "anchors", "ms", "whole-vis", "gray-map");
  int scored = 0;
  std::vector<eval::MiddleburyScene> scenes(eval::middlebury_scenes().begin(),
                                            eval::middlebury_scenes().end());
  scenes.insert(scenes.end(), eval::real_rock_scenes().begin(), eval::real_rock_scenes().end());
  for (const eval::MiddleburyScene& s : scenes) {
    if (!o.scene.empty() && o.scene != s.name) continue;
    auto data = eval::load_middlebury(s, o.data);
    if (!data) return fail("middlebury", data.error().message);
    if (perturbation.active()) eval::perturb(data->right, perturbation);
    MatchDpParams p;
    p.disp_min = 0;
    p.disp_max = s.disp_max;
    p.edge_constraint = !o.no_edges;
    p.normalise_gray = o.normalise;
    const auto t0 = std::chrono::steady_clock::now();
    auto run = eval::run_match_dp(data->left.view(), data->right.view(),
                                  Rect{0, 0, data->left.width, data->left.height}, p);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!run) return fail("middlebury", run.error().message);
    auto score = eval::score_middlebury(run->disparity.view(), *data);
    if (!score) return fail("middlebury", score.error().message);
    std::printf("%-9s %9.2f %9.2f %9.2f %9.2f %8.2f %8ld %8.1f %9.2f %6.3f/%+6.1f\n", s.name,
                score->strict.nonocc, score->strict.all, score->filled.nonocc, score->filled.all,
                score->invalid_pct, run->stats.anchors, ms, score->filled_whole_visible,
                run->stats.gray_gain_q8 / 256.0, run->stats.gray_offset_q8 / 256.0);
    ++scored;
  }
  if (scored == 0) return fail("middlebury", ("unknown scene \"" + o.scene + "\"").c_str());
  return 0;
}

}  // namespace

void add_middlebury(CLI::App& app, Outcome& outcome) {
  auto* cmd = app.add_subcommand("middlebury",
                                 "Score the DP matcher on the Middlebury scenes (bad-1 table)");
  static MiddleburyOptions o;
  cmd->add_option("--data", o.data, "shared data folder holding middlebury/ and middlebury2006/");
  cmd->add_option("--scene", o.scene,
                  "one scene (tsukuba, venus, sawtooth, map, teddy, cones, Aloe, Baby1, Rocks1)");
  cmd->add_flag("--no-edges", o.no_edges, "skip the edge constraint (for comparisons)");
  cmd->add_flag("--normalise,!--no-normalise", o.normalise,
                "map the right view's gray levels to the left's first (the default; "
                "algo/stereo/match_photometric); --no-normalise compares raw levels");
  cmd->add_option("--perturb", o.perturb,
                  "change the right view before matching: gain,offset,sigma[,seed[,vignetting]] "
                  "(e.g. 0.82,12,2: another camera's gain and offset, noise sigma 2)");
  cmd->callback([&outcome] { outcome.exit_code = run(o); });
}

}  // namespace petra::cli
