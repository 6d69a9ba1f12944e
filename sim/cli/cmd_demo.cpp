// `petra demo`: the README's main job (sim/demo/demo.hpp).
#include <cstdio>
#include <filesystem>
#include <string>

#include "sim/cli/commands.hpp"
#include "sim/demo/demo.hpp"

namespace petra::cli {

void add_demo(CLI::App& app, Outcome& outcome) {
  auto* sub =
      app.add_subcommand("demo", "Run petra-fsw on a scene: ROI in, grind planes and pictures out");
  static demo::Options options;
  sub->add_option("--out", options.out_dir, "output folder")->capture_default_str();
  sub->add_option("--scene", options.scene_dir,
                  "scene folder (left, right, calib.json, truth.json); default: simulate one");
  sub->add_option("--seed", options.seed, "simulated scene seed")->capture_default_str();
  sub->add_option("--fsw", options.fsw_binary,
                  "petra-fsw executable (default: beside petra, then PATH)");
  sub->add_option("--timeout-s", options.timeout_s, "evaluation time limit")->capture_default_str();
  sub->callback([&outcome] {
    options.self_binary = std::filesystem::canonical("/proc/self/exe").string();
    outcome.exit_code = demo::run(options, stdout);
  });
}

}  // namespace petra::cli
