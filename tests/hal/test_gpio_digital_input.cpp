// The e-stop line as the executive's DigitalInput: level, a short press
// reported once, an unreadable line as an error.
#include "hal/gpio_digital_input.hpp"

#include <gtest/gtest.h>

#include "hal/gpio_sim.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra::hal {
namespace {

TEST(GpioDigitalInput, AssertedWhileActive) {
  SimGpioInput line;
  GpioDigitalInput in(line);
  EXPECT_FALSE(*in.read());
  line.drive(true);
  EXPECT_TRUE(*in.read());
  EXPECT_TRUE(*in.read());  // still held
  line.drive(false);
  EXPECT_FALSE(*in.read());
}

TEST(GpioDigitalInput, AShortPressIsReportedOnce) {
  SimGpioInput line;
  GpioDigitalInput in(line);
  line.drive(true);
  line.drive(false);
  test::HeapScope heap;
  EXPECT_TRUE(*in.read());
  EXPECT_FALSE(*in.read());
  EXPECT_EQ(heap.allocations(), 0u);
  EXPECT_EQ(in.state().presses, 1u);
}

TEST(GpioDigitalInput, AnUnreadableLineIsAnError) {
  SimGpioInput line;
  GpioDigitalInput in(line);
  line.disconnect();
  auto r = in.read();
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.code(), Errc::io_error);
}

}  // namespace
}  // namespace petra::hal
