#include "fsw/health.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "tests/fsw/executive_harness.hpp"

namespace petra::fsw {
namespace {

constexpr std::int64_t kMs = 1000000;

TEST(Health, ReportsASilentComponentOnceUntilItBeatsAgain) {
  Health h;
  h.reset(0);
  std::array<std::int64_t, kComponentCount> timeout{};
  timeout.fill(100 * kMs);
  std::int64_t silent = 0;
  for (std::size_t c = 0; c < kComponentCount; ++c)
    if (c != static_cast<std::size_t>(Component::UPLINK))
      h.beat(static_cast<Component>(c), 150 * kMs);
  EXPECT_EQ(h.check(150 * kMs, timeout, silent), static_cast<int>(Component::UPLINK));
  EXPECT_EQ(silent, 150 * kMs);
  EXPECT_EQ(h.check(160 * kMs, timeout, silent), -1);  // reported once
  h.beat(Component::UPLINK, 170 * kMs);
  EXPECT_EQ(h.check(180 * kMs, timeout, silent), -1);
}

TEST(Health, ExemptComponentIsNotReported) {
  Health h;
  h.reset(0);
  std::array<std::int64_t, kComponentCount> timeout{};
  timeout.fill(100 * kMs);
  for (std::size_t c = 0; c < kComponentCount; ++c) h.beat(static_cast<Component>(c), 1000 * kMs);
  h.set_exempt(Component::WORKER, true, 0);
  std::int64_t silent = 0;
  EXPECT_EQ(h.check(1050 * kMs, timeout, silent), -1);
  h.set_exempt(Component::WORKER, false, 1050 * kMs);
  EXPECT_EQ(h.check(1100 * kMs, timeout, silent), -1);
}

TEST(Watchdog, EveryLoopCycleKicksTheConfiguredDevice) {
  test::ExecutiveHarness h;
  h.loop = R"({"cycle_ms":10,"watchdog_device":"wd"})";
  std::ofstream(h.dir() / "wd").flush();  // a plain file stands in for /dev/watchdog
  ASSERT_TRUE(h.boot().ok());
  h.cycles(25);
  EXPECT_EQ(h.exec().watchdog_kicks(), 25u);
  h.exec().shutdown();
  std::ifstream f(h.dir() / "wd");
  std::string s;
  f >> s;
  std::string kicks(25, 'k');
  kicks.push_back('V');  // kicks, then the magic close of a clean stop
  EXPECT_EQ(s, kicks);
}

}  // namespace
}  // namespace petra::fsw
