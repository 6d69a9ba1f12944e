// The `petra` ground CLI: one file per subcommand, each registering itself on
// the app. A subcommand reports failure by printing one line on stderr and
// setting a non-zero exit code; main turns usage errors into exit 2
// (docs/ops.md "Command line conventions").
#pragma once

#include <CLI/CLI.hpp>

namespace petra::cli {

// Set by a subcommand's callback; main returns it.
struct Outcome {
  int exit_code = 0;
};

void add_info(CLI::App& app, Outcome& outcome);
void add_sim(CLI::App& app, Outcome& outcome);
void add_score(CLI::App& app, Outcome& outcome);
void add_stereo(CLI::App& app, Outcome& outcome);
void add_middlebury(CLI::App& app, Outcome& outcome);
void add_cmd(CLI::App& app, Outcome& outcome);
void add_tlm(CLI::App& app, Outcome& outcome);
void add_keygen(CLI::App& app, Outcome& outcome);
void add_icd(CLI::App& app, Outcome& outcome);
void add_demo(CLI::App& app, Outcome& outcome);
void add_calib(CLI::App& app, Outcome& outcome);
void add_click(CLI::App& app, Outcome& outcome);
void add_gnd(CLI::App& app, Outcome& outcome);
void add_eval(CLI::App& app, Outcome& outcome);
void add_propose(CLI::App& app, Outcome& outcome);
// Registers `name` on `app`; `petra sim arm` = add_arm_sim(sim_subcommand, outcome, "arm").
void add_arm_sim(CLI::App& app, Outcome& outcome, const char* name = "sim-arm");
void add_arm_view(CLI::App& app, Outcome& outcome);
void add_archive(CLI::App& app, Outcome& outcome);

// Prints "petra <cmd>: <message>" on stderr and returns the exit code 1.
int fail(const char* cmd, const char* message);

}  // namespace petra::cli
