// libgpiod backend. Configuration errors are checked everywhere; the line
// tests need the bench's gpio-sim chip (label "petra-hil", lines cam_trigger,
// arm_power, estop): on a host without it they skip, and the HIL guest runs
// them, driving and watching the lines from the gpio-sim side in sysfs.
#include "hal/gpio_gpiod.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <thread>

#include "hal/estop_monitor.hpp"
#include "tests/hal/hil_devices.hpp"
#include "tests/hal/thread_probe.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra::hal {
namespace {

GpioLineConfig line_config(const std::string& chip, const char* line, bool active_low = false) {
  GpioLineConfig c;
  std::snprintf(c.chip.data(), c.chip.size(), "%s", chip.c_str());
  std::snprintf(c.line.data(), c.line.size(), "%s", line);
  c.active_low = active_low;
  return c;
}

TEST(GpiodConfig, EmptyNamesAndUnopenedLinesAreErrors) {
  GpiodOutput out;
  EXPECT_EQ(out.open(line_config("", "x"), "t", false).code(), Errc::missing_field);
  EXPECT_EQ(out.open(line_config("chip", ""), "t", false).code(), Errc::missing_field);
  EXPECT_EQ(out.set(true).code(), Errc::not_ready);
  GpiodInput in;
  EXPECT_EQ(in.read().code(), Errc::not_ready);
  GpioEvent ev;
  EXPECT_EQ(in.wait_event(ev, 0).code(), Errc::not_ready);
}

TEST(GpiodConfig, AMissingChipIsAnErrorNamingIt) {
  GpiodInput in;
  auto s = in.open(line_config("no-such-chip-label", "estop"), "t");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.code(), gpiod_available() ? Errc::io_error : Errc::not_ready);
  EXPECT_NE(std::strstr(s.error().message, "no-such-chip-label"), nullptr) << s.error().message;
}

class GpiodOnGpioSim : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!gpiod_available()) GTEST_SKIP() << "skipped: built without libgpiod";
    chip_ = test::find_gpio_chip(test::gpio_chip());
    if (chip_.name.empty())
      GTEST_SKIP() << "skipped: no gpio chip labelled '" << test::gpio_chip()
                   << "' (the HIL bench creates it with gpio-sim)";
    sim_ = test::gpio_sim_dir(chip_.name);
    ASSERT_FALSE(sim_.empty()) << chip_.name << " is not a gpio-sim chip";
  }
  std::string sim_file(const char* line, const char* what) {
    const int off = test::gpio_line_offset(chip_.name, line);
    EXPECT_GE(off, 0) << "no line " << line;
    return sim_ + "/sim_gpio" + std::to_string(off) + "/" + what;
  }

  test::GpioChipInfo chip_;
  std::string sim_;
};

TEST_F(GpiodOnGpioSim, ArmPowerOutputDrivesTheLine) {
  GpiodOutput power;
  ASSERT_TRUE(power.open(line_config(test::gpio_chip(), "arm_power"), "petra-test", false).ok());
  const std::string value = sim_file("arm_power", "value");
  EXPECT_EQ(test::read_text(value), "0");
  {
    test::HeapScope heap;
    ASSERT_TRUE(power.set(true).ok());
    EXPECT_EQ(heap.allocations(), 0u);
  }
  EXPECT_EQ(test::read_text(value), "1");
  ASSERT_TRUE(power.set(false).ok());
  EXPECT_EQ(test::read_text(value), "0");
}

TEST_F(GpiodOnGpioSim, ActiveLowOutputIsInvertedOnTheWire) {
  GpiodOutput out;
  ASSERT_TRUE(
      out.open(line_config(test::gpio_chip(), "arm_power", true), "petra-test", false).ok());
  const std::string value = sim_file("arm_power", "value");
  EXPECT_EQ(test::read_text(value), "1");  // inactive = high
  ASSERT_TRUE(out.set(true).ok());
  EXPECT_EQ(test::read_text(value), "0");
}

TEST_F(GpiodOnGpioSim, TriggerPulseIsSeenOnTheWire) {
  PETRA_REQUIRE_THREADS();
  GpiodOutput trigger;
  ASSERT_TRUE(
      trigger.open(line_config(test::gpio_chip(), "cam_trigger"), "petra-test", false).ok());
  const std::string value = sim_file("cam_trigger", "value");
  // Watch the wire from the gpio-sim side while the pulse runs.
  std::atomic<bool> stop{false};
  std::atomic<int> highs{0}, lows_after_high{0};
  std::thread watcher([&] {
    const int fd = ::open(value.c_str(), O_RDONLY | O_CLOEXEC);
    char c = 0;
    bool seen_high = false;
    while (!stop.load() && fd >= 0) {
      if (::pread(fd, &c, 1, 0) == 1) {
        if (c == '1') {
          seen_high = true;
          ++highs;
        } else if (seen_high) {
          ++lows_after_high;
        }
      }
    }
    if (fd >= 0) ::close(fd);
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_TRUE(pulse(trigger, 50'000).ok());
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  stop = true;
  watcher.join();
  EXPECT_GT(highs.load(), 0) << "the pulse never showed on the wire";
  EXPECT_GT(lows_after_high.load(), 0) << "the line stayed high after the pulse";
  EXPECT_EQ(test::read_text(value), "0");
}

TEST_F(GpiodOnGpioSim, EstopInputReadsAndWaitsForTheEdge) {
  const std::string pull = sim_file("estop", "pull");
  ASSERT_TRUE(test::write_text(pull, "pull-up"));  // normally closed loop: high = not pressed
  GpiodInput estop;
  ASSERT_TRUE(estop.open(line_config(test::gpio_chip(), "estop", true), "petra-test").ok());
  ASSERT_TRUE(estop.read().ok());
  EXPECT_FALSE(*estop.read());
  GpioEvent ev;
  EXPECT_FALSE(*estop.wait_event(ev, 0));  // nothing pending
  // The presser is another process, as the real e-stop is outside this one: a
  // thread of ours would be counted, and its first touch of thread-local storage
  // allocates (ASan's runtime, glibc's dynamic TLS) while the waiter is measured.
  const int pull_fd = ::open(pull.c_str(), O_WRONLY | O_CLOEXEC);
  ASSERT_GE(pull_fd, 0);
  const pid_t presser = ::fork();
  ASSERT_GE(presser, 0);
  if (presser == 0) {
    ::usleep(50'000);
    const char text[] = "pull-down";  // the loop opens: e-stop pressed
    const bool wrote = ::write(pull_fd, text, sizeof text - 1) == ssize_t{sizeof text - 1};
    ::_exit(wrote ? 0 : 1);
  }
  Result<bool> got = false;
  {
    test::HeapScope heap;
    got = estop.wait_event(ev, 5000);
    EXPECT_EQ(heap.allocations(), 0u);
  }
  int status = -1;
  ASSERT_EQ(::waitpid(presser, &status, 0), presser);
  ::close(pull_fd);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the presser's write failed";
  ASSERT_TRUE(got.ok()) << got.error().message;
  ASSERT_TRUE(*got) << "no edge within 5 s";
  EXPECT_EQ(ev.edge, GpioEdge::rising);  // logical: became active
  EXPECT_GT(ev.time_ns, 0);
  EXPECT_TRUE(*estop.read());
  ASSERT_TRUE(test::write_text(pull, "pull-up"));
  ASSERT_TRUE(*estop.wait_event(ev, 5000));
  EXPECT_EQ(ev.edge, GpioEdge::falling);
  EXPECT_FALSE(*estop.read());
}

TEST_F(GpiodOnGpioSim, EstopMonitorCatchesAPressReleasedBeforeThePoll) {
  const std::string pull = sim_file("estop", "pull");
  ASSERT_TRUE(test::write_text(pull, "pull-up"));
  GpiodInput estop;
  ASSERT_TRUE(estop.open(line_config(test::gpio_chip(), "estop", true), "petra-test").ok());
  EstopMonitor monitor(estop);
  EXPECT_FALSE(monitor.poll().latched);
  ASSERT_TRUE(test::write_text(pull, "pull-down"));  // pressed...
  ASSERT_TRUE(test::write_text(pull, "pull-up"));    // ...and released between two polls
  // The executive polls every cycle; the kernel's edge handling runs in its own
  // thread, so give it a few 10 ms cycles.
  EstopState s;
  {
    test::HeapScope heap;
    for (int cycle = 0; cycle < 100 && !s.latched; ++cycle) {
      s = monitor.poll();
      if (!s.latched) usleep(10'000);
    }
    EXPECT_EQ(heap.allocations(), 0u);
  }
  EXPECT_FALSE(s.line_fault) << monitor.last_error().message;
  EXPECT_FALSE(s.asserted);
  EXPECT_TRUE(s.latched) << "a press released before the poll was missed";
  EXPECT_GE(s.presses, 1u);
}

TEST_F(GpiodOnGpioSim, UnknownLineAndBusyLineAreErrorsNamingThem) {
  GpiodInput in;
  auto s = in.open(line_config(test::gpio_chip(), "no_such_line"), "petra-test");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(std::strstr(s.error().message, "no_such_line"), nullptr) << s.error().message;
  GpiodOutput a, b;
  ASSERT_TRUE(a.open(line_config(test::gpio_chip(), "cam_trigger"), "first", false).ok());
  auto busy = b.open(line_config(test::gpio_chip(), "cam_trigger"), "second", false);
  ASSERT_FALSE(busy.ok());
  EXPECT_EQ(busy.code(), Errc::io_error);
  EXPECT_NE(std::strstr(busy.error().message, "cannot request"), nullptr) << busy.error().message;
}

}  // namespace
}  // namespace petra::hal
