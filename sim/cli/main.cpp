// petra: the ground CLI (sim, stereo, eval, score, calib, cmd, tlm, demo, ...).
// Conventions (docs/ops.md "Command line conventions"): exit 0 on success,
// 1 with one line "petra <command>: <reason>" on stderr when the work fails
// (a bad value included), 2 with the same kind of line for a command line
// that does not parse; --help and --version exit 0.
#include <cstdio>
#include <exception>
#include <string>

#include "sim/cli/commands.hpp"

#ifndef PETRA_VERSION
#define PETRA_VERSION "unknown"
#endif

namespace petra::cli {

namespace {

int report(const char* cmd, const char* message, int code) {
  std::fflush(stdout);  // what was printed before the failure comes first in a shared log
  std::fprintf(stderr, "petra%s%s: %s\n", cmd[0] != '\0' ? " " : "", cmd, message);
  return code;
}

// "eval", "gnd serve", or "" when argv names no subcommand: the deepest
// subcommand named on the command line, for the prefix of an error line.
std::string command_path(CLI::App& app, int argc, char** argv) {
  std::string path;
  CLI::App* current = &app;
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    for (CLI::App* sub : current->get_subcommands([](CLI::App*) { return true; })) {
      if (!sub->check_name(word)) continue;
      path += (path.empty() ? "" : " ") + sub->get_name();
      current = sub;
      break;
    }
  }
  return path;
}

// A usage error CLI11 found (unknown option, missing required option, a value
// of the wrong type, an unexpected argument): the line points to --help.
int usage_error(const char* cmd, const std::string& message) {
  const std::string help = std::string(" (see petra ") + cmd + (cmd[0] ? " " : "") + "--help)";
  return report(cmd, (message + help).c_str(), 2);
}

}  // namespace

int fail(const char* cmd, const char* message) {
  return report(cmd, message, 1);
}

}  // namespace petra::cli

int main(int argc, char** argv) {
  CLI::App app{"petra: ground tools for the Petra rock-sampling arm"};
  app.name("petra");
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("petra ") + PETRA_VERSION);
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
  petra::cli::add_propose(app, outcome);
  petra::cli::add_arm_sim(app, outcome);
  petra::cli::add_arm_view(app, outcome);
  petra::cli::add_archive(app, outcome);
  const std::string cmd = petra::cli::command_path(app, argc, argv);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);    // --help, --version
    if (cmd.empty() && argc > 1 && argv[1][0] != '-')  // CLI11 says "A subcommand is required"
      return petra::cli::usage_error("", std::string("unknown command '") + argv[1] + "'");
    return petra::cli::usage_error(cmd.c_str(), e.what());
  } catch (const std::exception& e) {  // a subcommand's failure it did not catch itself
    return petra::cli::fail(cmd.c_str(), e.what());
  }
  return outcome.exit_code;
}
