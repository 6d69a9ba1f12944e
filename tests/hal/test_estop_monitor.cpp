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
