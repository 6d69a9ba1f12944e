// `petra demo` on a scene folder: every step is announced, and the outcome
// is either the grind planes or the reason there are none (here: no calib.json).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace petra {
namespace {

namespace fs = std::filesystem;

TEST(Demo, NarratesEachStepAndEndsWithTheReasonWhenThereAreNoPlanes) {
  const fs::path dir = fs::temp_directory_path() / ("petra_demo_" + std::to_string(::getpid()));
  fs::create_directories(dir / "scene");
  for (const char* name : {"left", "right"}) {
    std::ofstream f(dir / "scene" / (std::string(name) + ".pgm"), std::ios::binary);
    f << "P5\n160 120\n255\n";
    for (int i = 0; i < 160 * 120; ++i) f.put(static_cast<char>(i % 251));
  }
  std::ofstream(dir / "scene/truth.json") << R"({"roi":[20,10,100,80],"planes":2})";
  const std::string cmd = std::string(PETRA_CLI_BIN) + " demo --fsw " + PETRA_FSW_BIN +
                          " --scene " + (dir / "scene").string() + " --out " +
                          (dir / "out").string() + " --timeout-s 60 > " +
                          (dir / "demo.txt").string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  std::stringstream text;
  text << std::ifstream(dir / "demo.txt").rdbuf();
  const std::string out = text.str();
  EXPECT_NE(out.find("2. petra-fsw started"), std::string::npos) << out;
  EXPECT_NE(out.find("3. sent SELECT_ROI x 20, y 10, 100 x 80 px, c = 2"), std::string::npos)
      << out;
  EXPECT_NE(out.find("4. sent EVALUATE"), std::string::npos) << out;
  const bool planes = out.find("5. evaluation") != std::string::npos;
  // The scene has no calib.json: the flight pipeline says so by name.
  EXPECT_FALSE(planes) << out;
  EXPECT_NE(out.find("failed: not_ready in step RECTIFY"), std::string::npos) << out;
  EXPECT_NE(out.find("demo stopped: EVALUATE FAILED: PIPELINE_ERROR"), std::string::npos) << out;
  EXPECT_NE(status, 0) << out;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace petra
