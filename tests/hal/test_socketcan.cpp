// SocketCAN backend. The error-frame decoding is pure and runs everywhere; the
// socket tests need a kernel with AF_CAN and a vcan interface (PETRA_CAN_IF,
// default vcan0): on hosts without them they are skipped, saying so, and the
// HIL bench runs them.
#include "hal/socketcan.hpp"

#include <gtest/gtest.h>

#include <linux/can.h>
#include <linux/can/error.h>

#include <array>
#include <cstdlib>
#include <string>

#include "tests/support/heap_counter.hpp"

namespace petra::hal {
namespace {

const char* interface_name() {
  const char* env = std::getenv("PETRA_CAN_IF");
  return env != nullptr ? env : "vcan0";
}

#define PETRA_REQUIRE_VCAN()                                                   \
  do {                                                                         \
    if (!socketcan_available())                                                \
      GTEST_SKIP() << "skipped: AF_CAN not available (runs in the HIL bench)"; \
  } while (false)

TEST(SocketCanErrors, ControllerStatesAndBusOffFollowTheErrorFrames) {
  CanHealth h;
  std::array<std::uint8_t, 8> d{};
  d[1] = CAN_ERR_CRTL_TX_WARNING;
  apply_error_frame(CAN_ERR_FLAG | CAN_ERR_CRTL, d, h);
  EXPECT_EQ(h.state, CanBusState::error_warning);
  d[1] = CAN_ERR_CRTL_RX_PASSIVE;
  apply_error_frame(CAN_ERR_FLAG | CAN_ERR_CRTL, d, h);
  EXPECT_EQ(h.state, CanBusState::error_passive);
  d[1] = 0;
  apply_error_frame(CAN_ERR_FLAG | CAN_ERR_BUSOFF, d, h);
  EXPECT_EQ(h.state, CanBusState::bus_off);
  EXPECT_EQ(h.bus_off_count, 1u);
  apply_error_frame(CAN_ERR_FLAG | CAN_ERR_BUSOFF, d, h);  // still the same bus-off
  EXPECT_EQ(h.bus_off_count, 1u);
  apply_error_frame(CAN_ERR_FLAG | CAN_ERR_RESTARTED, d, h);
  EXPECT_EQ(h.state, CanBusState::error_active);
  EXPECT_EQ(h.restarts, 1u);
  d[1] = CAN_ERR_CRTL_RX_OVERFLOW;
  apply_error_frame(CAN_ERR_FLAG | CAN_ERR_CRTL, d, h);
  EXPECT_EQ(h.rx_dropped, 1u);
  apply_error_frame(CAN_ERR_FLAG | CAN_ERR_PROT | CAN_ERR_BUSERROR, d, h);
  EXPECT_EQ(h.error_frames, 7u);
  EXPECT_EQ(h.last_error_class, CAN_ERR_PROT | CAN_ERR_BUSERROR);
  EXPECT_EQ(h.state, CanBusState::error_active);
}

TEST(SocketCan, OpenFailsCleanlyWithoutTheInterface) {
  SocketCanPort p;
  EXPECT_EQ(p.open("").code(), Errc::invalid_argument);
  EXPECT_EQ(p.open("a-name-much-too-long-for-linux").code(), Errc::invalid_argument);
  // Not open: both directions refuse with not_ready.
  CanFrame f;
  EXPECT_EQ(p.send(f).code(), Errc::not_ready);
  EXPECT_EQ(p.receive(f, 0).code(), Errc::not_ready);
  // Without AF_CAN, or with no such interface, open() is an io_error naming it.
  auto s = p.open("nosuchcan7");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.code(), Errc::io_error);
  EXPECT_FALSE(p.is_open());
}

class SocketCanOnVcan : public ::testing::Test {
 protected:
  void SetUp() override {
    PETRA_REQUIRE_VCAN();
    auto s = a_.open(interface_name());
    if (!s.ok())
      GTEST_SKIP() << "skipped: " << s.error().message << " (the HIL bench creates vcan0)";
  }
  SocketCanPort a_;
};

TEST_F(SocketCanOnVcan, FramesGoBetweenTwoSocketsAndNotBackToTheSender) {
  SocketCanPort b;
  ASSERT_TRUE(b.open(interface_name()).ok());
  CanFrame f;
  f.id = 0x601;
  f.len = 8;
  f.data = {0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0};
  ASSERT_TRUE(a_.send(f).ok());
  CanFrame got;
  auto r = b.receive(got, 1000);
  ASSERT_TRUE(r.ok() && *r);
  EXPECT_EQ(got.id, 0x601u);
  EXPECT_EQ(got.len, 8);
  EXPECT_EQ(got.data, f.data);
  r = a_.receive(got, 0);
  ASSERT_TRUE(r.ok());
  EXPECT_FALSE(*r);
  EXPECT_EQ(a_.health().frames_sent, 1u);
  EXPECT_EQ(b.health().frames_received, 1u);
}

TEST_F(SocketCanOnVcan, KernelFiltersDropOtherIds) {
  SocketCanPort b;
  const CanFilter only_0x181[] = {{0x181, 0x7FF}};
  ASSERT_TRUE(b.open(interface_name(), only_0x181).ok());
  CanFrame f;
  f.len = 1;
  f.id = 0x182;
  ASSERT_TRUE(a_.send(f).ok());
  f.id = 0x181;
  ASSERT_TRUE(a_.send(f).ok());
  CanFrame got;
  auto r = b.receive(got, 1000);
  ASSERT_TRUE(r.ok() && *r);
  EXPECT_EQ(got.id, 0x181u);
  r = b.receive(got, 20);
  ASSERT_TRUE(r.ok());
  EXPECT_FALSE(*r);
}

TEST_F(SocketCanOnVcan, ReceiveTimesOutWithFalseAndSendRefusesBadFrames) {
  CanFrame got;
  auto r = a_.receive(got, 30);
  ASSERT_TRUE(r.ok());
  EXPECT_FALSE(*r);
  CanFrame bad;
  bad.id = 0x900;
  EXPECT_EQ(a_.send(bad).code(), Errc::invalid_argument);
}

TEST_F(SocketCanOnVcan, SteadyTrafficDoesNotAllocate) {
  SocketCanPort b;
  ASSERT_TRUE(b.open(interface_name()).ok());
  CanFrame f;
  f.id = 0x201;
  f.len = 6;
  test::HeapScope scope;
  CanFrame got;
  for (int i = 0; i < 200; ++i) {
    ASSERT_TRUE(a_.send(f).ok());
    auto r = b.receive(got, 100);
    ASSERT_TRUE(r.ok() && *r);
  }
  EXPECT_EQ(scope.allocations(), 0u);
}

}  // namespace
}  // namespace petra::hal
