// The command line conventions (docs/ops.md "Command line conventions"), each
// case of issue 25 run through the built executables: the exit status and the
// one line on stderr, prefixed with the command.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace petra {
namespace {

namespace fs = std::filesystem;

// <build>/sim/petra and <build>/fsw/petra-fsw beside <build>/tests.
fs::path build_dir() {
  std::array<char, 4096> buf{};
  const ssize_t n = readlink("/proc/self/exe", buf.data(), buf.size() - 1);
  return fs::path(std::string(buf.data(), static_cast<std::size_t>(n > 0 ? n : 0)))
      .parent_path()
      .parent_path();
}

struct CliOutcome {
  int status = -1;
  std::string out, err;
};

class CliConventions : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("petra_cli_conv_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  CliOutcome run(const std::string& binary, const std::string& args) {
    const fs::path out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    const std::string cmd = (build_dir() / binary).string() + " " + args + " > " + out.string() +
                            " 2> " + err.string() + " < /dev/null";
    const int rc = std::system(cmd.c_str());
    CliOutcome r;
    r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
    std::ifstream fo(out), fe(err);
    std::stringstream so, se;
    so << fo.rdbuf();
    se << fe.rdbuf();
    r.out = so.str();
    r.err = se.str();
    return r;
  }
  CliOutcome petra(const std::string& args) { return run("sim/petra", args); }
  CliOutcome fsw(const std::string& args) { return run("fsw/petra-fsw", args); }

  fs::path dir_;
};

// One line on stderr, starting with `prefix` and containing `text`.
void expect_line(const CliOutcome& r, int status, const std::string& prefix,
                 const std::string& text) {
  EXPECT_EQ(r.status, status) << r.err;
  EXPECT_EQ(r.err.rfind(prefix, 0), 0u) << r.err;
  EXPECT_NE(r.err.find(text), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
}

TEST_F(CliConventions, UsageErrorsExit2NamingTheCommand) {
  expect_line(petra(""), 2, "petra: ", "subcommand");
  expect_line(petra("fly"), 2, "petra: ", "unknown command 'fly' (see petra --help)");
  expect_line(petra("eval --calib c.json"), 2,
              "petra eval: ", "is required (see petra eval --help)");
  expect_line(petra("info --calib c.json --bogus 1"), 2, "petra info: ", "--bogus");
  expect_line(petra("stereo --left a --right b --disp-min x --disp-max 5 --out o.pfm"), 2,
              "petra stereo: ", "--disp-min");
  expect_line(petra("gnd serve --port eighty"), 2, "petra gnd serve: ", "--port");
  expect_line(petra("cmd"), 2, "petra cmd: ", "name");
}

TEST_F(CliConventions, HelpAndVersionExit0) {
  for (const char* args : {"--help", "eval --help", "gnd serve --help", "cmd --help"}) {
    const CliOutcome r = petra(args);
    EXPECT_EQ(r.status, 0) << args << ": " << r.err;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << args;
  }
  CliOutcome r = petra("--version");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out.rfind("petra ", 0), 0u) << r.out;
  EXPECT_NE(r.out.find('.'), std::string::npos) << r.out;
  r = fsw("--version");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out.rfind("petra-fsw ", 0), 0u) << r.out;
  r = fsw("--help");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("--config FILE"), std::string::npos) << r.out;
}

TEST_F(CliConventions, PetraFswUsageErrorsExit2) {
  CliOutcome r = fsw("--confg x.json");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err.rfind("petra-fsw: unknown argument '--confg'\n", 0), 0u) << r.err;
  r = fsw("");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err.rfind("petra-fsw: --config FILE is required\n", 0), 0u) << r.err;
}

TEST_F(CliConventions, PetraFswRefusesAnUnknownConfigurationKeyByName) {
  std::ofstream(dir_ / "fsw.json")
      << R"({"upink":{"key_file":"k"},"uplink":{"key_file":"k"},"camera":{"dir":"pairs"}})";
  const CliOutcome r = fsw("--config " + (dir_ / "fsw.json").string());
  expect_line(r, 1, "petra-fsw: config: upink: unknown key", "expected one of uplink, downlink");
}

TEST_F(CliConventions, PetraFswConfigFileErrorsSayWhy) {
  const CliOutcome r = fsw("--config " + (dir_ / "absent.json").string());
  expect_line(r, 1, "petra-fsw: ", "absent.json: cannot open (No such file or directory)");
  expect_line(fsw("--config " + dir_.string()), 1,
              "petra-fsw: ", dir_.string() + ": cannot read (Is a directory)");
}

// Was an uncaught std::filesystem::filesystem_error: abort, exit 134.
TEST_F(CliConventions, DemoIntoAnUnwritablePlaceFailsWithTheReason) {
  std::ofstream(dir_ / "a_file") << "x";
  const CliOutcome r = petra("demo --out " + (dir_ / "a_file" / "demo").string());
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("petra demo: cannot create the output folder " +
                       (dir_ / "a_file" / "demo" / "pairs").string() + ": Not a directory"),
            std::string::npos)
      << r.err;
}

TEST_F(CliConventions, FileErrorsNameTheFileAndTheReason) {
  expect_line(petra("info --calib " + (dir_ / "absent.json").string()), 1,
              "petra info: ", "absent.json: No such file or directory");
  // A directory given as calib.json (was "file too large").
  expect_line(petra("info --calib " + dir_.string()), 1,
              "petra info: ", dir_.string() + ": is a directory, not a file");
  expect_line(petra("stereo --left " + (dir_ / "l.png").string() +
                    " --right r.png --disp-min 0 "
                    "--disp-max 9 --out o.pfm"),
              1, "petra stereo: ", "l.png: No such file or directory");
  expect_line(petra("cmd --key " + (dir_ / "absent.key").string() + " NOOP"), 1,
              "petra cmd: ", "absent.key: No such file or directory");
}

// The matcher's own name stays out of an operator's message.
TEST_F(CliConventions, AnEmptyDisparityRangeIsNamedByItsOptions) {
  const CliOutcome r =
      petra("stereo --left a.png --right b.png --disp-min 10 --disp-max 5 --out o.pfm");
  expect_line(
      r, 1, "petra stereo: ", "--disp-min 10 is above --disp-max 5: the disparity range is empty");
  EXPECT_EQ(r.err.find("match_dp"), std::string::npos) << r.err;
}

TEST_F(CliConventions, CmdRequiresEveryFieldBeforeSending) {
  // Was sent with y_px, w_px, h_px and planes = 0.
  expect_line(petra("cmd SELECT_ROI x_px=10"), 1, "petra cmd: ",
              "SELECT_ROI: missing y_px, w_px, h_px, planes (every field is required)");
  expect_line(petra("cmd SELECT_ROI x_px=10 y_px=10 w_px=50 h_px=50 planes=2 click_u_px=20"), 1,
              "petra cmd: ", "click_u_px and click_v_px");
  expect_line(petra("cmd SELECT_ROI x_px=10 y_px=10 w_px=50 h_px=50 planes=2 click_u_px=5 "
                    "click_v_px=20"),
              1, "petra cmd: ", "outside the ROI");
  expect_line(petra("cmd SET_PARAM param_id=999 value=1"), 1,
              "petra cmd: ", "SET_PARAM.param_id = 999: no such parameter");
  expect_line(petra("cmd ARM_GOTO plane_rank=0 plane_rank=1 standoff_mm=50"), 1,
              "petra cmd: ", "given twice");
  expect_line(petra("cmd EVALUATE"), 1, "petra cmd: ", "EVALUATE: missing acquire");
}

}  // namespace
}  // namespace petra
