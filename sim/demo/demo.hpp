// `petra demo`: the whole chain as an operator sees it. Starts petra-fsw on a
// scene (from the simulator, or a folder given with --scene), sends SELECT_ROI
// and EVALUATE as signed telecommands, prints the grind planes that come back
// as telemetry and writes the pictures. Every step prints one line saying
// what happened, so a newcomer can follow it.
#pragma once

#include <cstdio>
#include <string>

namespace petra::demo {

struct Options {
  std::string out_dir = "petra-demo";
  std::string scene_dir;  // left.*, right.*, calib.json, truth.json; empty: run the simulator
  int seed = 1;
  std::string fsw_binary;   // empty: beside the petra executable, then PATH
  std::string self_binary;  // the petra executable (for `petra sim scene`)
  int timeout_s = 600;      // evaluation time limit
};

// Returns the exit status (0: planes received) and prints progress to out.
int run(const Options& options, std::FILE* out);

}  // namespace petra::demo
