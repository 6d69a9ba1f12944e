// The simulated GPIO twin and the pulse helper: a trigger pulse is one rising
// and one falling edge at least as long as asked; an e-stop edge reaches a
// waiting thread; broken lines end as error values.
#include "hal/gpio_sim.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <thread>

#include "tests/hal/thread_probe.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra::hal {
namespace {

TEST(GpioPulse, OneEdgeUpOneEdgeDownAtLeastAsLongAsAsked) {
  SimGpioOutput out;
  ASSERT_TRUE(pulse(out, 2000).ok());
  EXPECT_EQ(out.rising_edges(), 1u);
  EXPECT_EQ(out.falling_edges(), 1u);
  EXPECT_FALSE(out.level());
  EXPECT_GE(out.last_active_ns(), 2'000'000);
}

TEST(GpioPulse, RefusesWidthsOutsideTheRangeWithoutTouchingTheLine) {
  SimGpioOutput out;
  EXPECT_EQ(pulse(out, 0).code(), Errc::invalid_argument);
  EXPECT_EQ(pulse(out, 2'000'000).code(), Errc::invalid_argument);
  EXPECT_EQ(out.rising_edges(), 0u);
}

TEST(GpioPulse, ABrokenLineIsAnError) {
  SimGpioOutput out;
  out.disconnect();
  auto s = pulse(out, 10);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.code(), Errc::io_error);
}

TEST(GpioPulse, NoHeap) {
  SimGpioOutput out;
  test::HeapScope heap;
  for (int i = 0; i < 10; ++i) ASSERT_TRUE(pulse(out, 1).ok());
  EXPECT_EQ(heap.allocations(), 0u);
}

TEST(SimGpioInput, EdgesReachAWaitingThreadInOrder) {
  PETRA_REQUIRE_THREADS();
  SimGpioInput in;
  std::thread outside([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    in.drive(true);
    in.drive(false);
  });
  GpioEvent ev;
  auto got = in.wait_event(ev, 5000);
  ASSERT_TRUE(got.ok());
  ASSERT_TRUE(*got);
  EXPECT_EQ(ev.edge, GpioEdge::rising);
  ASSERT_TRUE(*in.wait_event(ev, 5000));
  EXPECT_EQ(ev.edge, GpioEdge::falling);
  outside.join();
  EXPECT_FALSE(*in.read());
}

TEST(SimGpioInput, TimeoutIsFalseNotAnError) {
  SimGpioInput in;
  GpioEvent ev;
  test::HeapScope heap;
  auto got = in.wait_event(ev, 0);
  ASSERT_TRUE(got.ok());
  EXPECT_FALSE(*got);
  auto later = in.wait_event(ev, 10);
  ASSERT_TRUE(later.ok());
  EXPECT_FALSE(*later);
  EXPECT_EQ(heap.allocations(), 0u);
  EXPECT_EQ(in.wait_event(ev, -1).code(), Errc::invalid_argument);
}

TEST(SimGpioInput, SameLevelIsNoEdgeAndAFullQueueCountsOverflows) {
  SimGpioInput in;
  in.drive(false);  // already inactive
  GpioEvent ev;
  EXPECT_FALSE(*in.wait_event(ev, 0));
  for (std::uint32_t i = 0; i < SimGpioInput::kQueueDepth + 3; ++i) in.drive(i % 2 == 0);
  EXPECT_EQ(in.overflows(), 3u);
  ASSERT_TRUE(*in.wait_event(ev, 0));
  EXPECT_EQ(ev.edge, GpioEdge::rising);  // the oldest edges are kept
}

TEST(SimGpioInput, DisconnectWakesTheWaiterWithAnError) {
  PETRA_REQUIRE_THREADS();
  SimGpioInput in;
  std::thread outside([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    in.disconnect();
  });
  GpioEvent ev;
  auto got = in.wait_event(ev, 5000);
  outside.join();
  ASSERT_FALSE(got.ok());
  EXPECT_EQ(got.code(), Errc::io_error);
  EXPECT_EQ(in.read().code(), Errc::io_error);
}

}  // namespace
}  // namespace petra::hal
