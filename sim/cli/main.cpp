// petra: the ground CLI (sim, stereo, eval, score, calib, cmd, tlm, demo, ...).
#include <cstdio>

#include "sim/cli/commands.hpp"

namespace petra::cli {

int fail(const char* cmd, const char* message) {
  std::fflush(stdout);  // what was printed before the failure comes first in a shared log
  std::fprintf(stderr, "petra %s: %s\n", cmd, message);
  return 1;
}

}  // namespace petra::cli

int main(int argc, char** argv) {
  CLI::App app{"petra: ground tools for the Petra rock-sampling arm"};
  app.require_subcommand(1);
  petra::cli::Outcome outcome;
  // One line per subcommand, each defined in its own cmd_<name>.cpp.
  petra::cli::add_info(app, outcome);
  petra::cli::add_sim(app, outcome);
  petra::cli::add_score(app, outcome);
  petra::cli::add_stereo(app, outcome);
  petra::cli::add_middlebury(app, outcome);
  petra::cli::add_cmd(app, outcome);
  petra::cli::add_tlm(app, outcome);
  petra::cli::add_keygen(app, outcome);
  petra::cli::add_icd(app, outcome);
  petra::cli::add_demo(app, outcome);
  petra::cli::add_calib(app, outcome);
  petra::cli::add_click(app, outcome);
  petra::cli::add_gnd(app, outcome);
  petra::cli::add_eval(app, outcome);
  petra::cli::add_arm_sim(app, outcome);
  petra::cli::add_arm_view(app, outcome);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  return outcome.exit_code;
}
