// The e-stop monitor on the simulated line: level, latch of a short press,
// unreadable line counted as pressed, no heap per poll.
#include "hal/estop_monitor.hpp"

#include <gtest/gtest.h>

#include "hal/gpio_sim.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra::hal {
namespace {

TEST(EstopMonitor, FollowsTheLevelAndLatchesUntilCleared) {
  SimGpioInput line;
  EstopMonitor m(line);
  EXPECT_FALSE(m.poll().asserted);
  line.drive(true);
  EstopState s = m.poll();
  EXPECT_TRUE(s.asserted);
  EXPECT_TRUE(s.latched);
  EXPECT_EQ(s.presses, 1u);
  line.drive(false);
  s = m.poll();
  EXPECT_FALSE(s.asserted);
  EXPECT_TRUE(s.latched);  // until the operator acknowledges
  m.clear_latch();
  EXPECT_FALSE(m.poll().latched);
}

TEST(EstopMonitor, APressShorterThanACycleIsStillCaught) {
  SimGpioInput line;
  EstopMonitor m(line);
  line.drive(true);
  line.drive(false);  // released before the next poll
  test::HeapScope heap;
  const EstopState s = m.poll();
  EXPECT_EQ(heap.allocations(), 0u);
  EXPECT_FALSE(s.asserted);
  EXPECT_TRUE(s.latched);
  EXPECT_EQ(s.presses, 1u);
}

// Two "falling" edges in a row: the kernel handled a fast press-release after
// the release (the sim twin cannot produce this order, so a scripted line does).
class ScriptedLine final : public GpioInput {
 public:
  Result<bool> read() override { return false; }
  Result<bool> wait_event(GpioEvent& out, int) override {
    if (left_ == 0) return false;
    --left_;
    out.edge = GpioEdge::falling;
    return true;
  }

 private:
  int left_ = 2;
};

TEST(EstopMonitor, AReleaseWhileReleasedMeansAMissedPress) {
  ScriptedLine line;
  EstopMonitor m(line);
  const EstopState s = m.poll();
  EXPECT_FALSE(s.asserted);
  EXPECT_TRUE(s.latched);
  EXPECT_EQ(s.presses, 2u);  // each release with no press before it
}

TEST(EstopMonitor, AnUnreadableLineCountsAsPressed) {
  SimGpioInput line;
  EstopMonitor m(line);
  line.disconnect();
  const EstopState s = m.poll();
  EXPECT_TRUE(s.line_fault);
  EXPECT_TRUE(s.asserted);
  EXPECT_TRUE(s.latched);
  EXPECT_EQ(m.last_error().code, Errc::io_error);
}

}  // namespace
}  // namespace petra::hal
