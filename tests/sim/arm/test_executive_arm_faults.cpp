// The executive's reactions to the arm's faults (docs/hal.md "Faults", docs/
// arm.md "In the executive"), with the flight arm over the loopback bus and the
// simulated drives: an e-stop through the GPIO twin (hal::SimGpioInput behind
// hal::GpioDigitalInput, as petra-fsw wires the libgpiod line), a drive EMCY,
// CAN bus errors (warning, passive, bus-off as SocketCAN error frames report
// them) and a malformed frame. The same reactions run in the HIL bench over
// vcan and gpio-sim (sim/hil/guest/checks/40-arm.sh).
#include <gtest/gtest.h>

#include <linux/can/error.h>

#include "hal/gpio_digital_input.hpp"
#include "hal/gpio_sim.hpp"
#include "tests/sim/arm/executive_arm_rig.hpp"

namespace petra {
namespace {

using cmd::FunctionCode;
using test::ArmRig;
using test::start_motion;

int count_events(const ArmRig& rig, EventId id) {
  int n = 0;
  for (const auto& e : rig.h.all<tlm::Event>()) n += e.event_id == static_cast<std::uint16_t>(id);
  return n;
}

bool has_event_with(const ArmRig& rig, EventId id, std::int32_t arg0, std::int32_t arg1) {
  for (const auto& e : rig.h.all<tlm::Event>())
    if (e.event_id == static_cast<std::uint16_t>(id) && e.args[0] == arg0 && e.args[1] == arg1)
      return true;
  return false;
}

void expect_all_drives_quick_stopped(ArmRig& rig) {
  rig.until([&] { return false; }, 30);
  for (int j = 0; j < 5; ++j)
    EXPECT_EQ(rig.drives.drive(j).drive_state(), canopen::DriveState::quick_stop_active)
        << "drive " << j + 1;
}

TEST(ExecutiveArmFaults, AnEStopPressOnTheGpioLineEndsInAQuickStopAndSafe) {
  ArmRig rig;
  hal::SimGpioInput line;
  hal::GpioDigitalInput estop(line);
  rig.h.estop = &estop;
  ASSERT_TRUE(rig.boot());
  cmd::Command go;
  start_motion(rig, go);
  // A press shorter than a cycle: pressed and released between two reads.
  line.drive(true);
  line.drive(false);
  rig.cycle();
  EXPECT_EQ(rig.h.exec().mode(), Mode::SAFE);
  EXPECT_EQ(count_events(rig, EventId::ESTOP_ASSERTED), 1);
  EXPECT_TRUE(rig.h.has_ack(go.counter, AckStage::FAILED));
  expect_all_drives_quick_stopped(rig);
  // A held press is one event, not one per cycle.
  line.drive(true);
  rig.until([&] { return false; }, 10);
  EXPECT_EQ(count_events(rig, EventId::ESTOP_ASSERTED), 2);
  // A broken line counts as pressed.
  line.drive(false);
  rig.until([&] { return false; }, 3);
  line.disconnect();
  rig.until([&] { return false; }, 3);
  EXPECT_EQ(count_events(rig, EventId::ESTOP_ASSERTED), 3);
  EXPECT_EQ(rig.h.exec().mode(), Mode::SAFE);
}

TEST(ExecutiveArmFaults, ADriveEmergencyEndsInSafeWithTheDriveAndItsCode) {
  ArmRig rig;
  ASSERT_TRUE(rig.boot());
  cmd::Command go;
  start_motion(rig, go);
  rig.drives.inject_fault(3, 0x2310);  // node 4: output overcurrent
  ASSERT_TRUE(rig.until([&] { return rig.h.exec().mode() == Mode::SAFE; }, 20));
  EXPECT_TRUE(has_event_with(rig, EventId::ARM_EMERGENCY, 4, 0x2310));
  bool fault_event = false;
  for (const auto& e : rig.h.all<tlm::Event>())
    fault_event |=
        e.event_id == static_cast<std::uint16_t>(EventId::ARM_DRIVE_FAULT) && e.args[0] == 4;
  EXPECT_TRUE(fault_event);
  EXPECT_TRUE(rig.h.has_ack(go.counter, AckStage::FAILED));
  EXPECT_EQ(rig.h.acks_for(go.counter).back().reason, static_cast<std::uint8_t>(Reason::ABORTED));
  rig.until([&] { return false; }, 30);
  for (int j = 0; j < 5; ++j) {
    if (j == 3) continue;  // the faulted drive is in Fault, the others ramp down
    EXPECT_EQ(rig.drives.drive(j).drive_state(), canopen::DriveState::quick_stop_active);
  }
}

TEST(ExecutiveArmFaults, BusErrorsAreReportedAndBusOffEndsInSafe) {
  ArmRig rig;
  ASSERT_TRUE(rig.boot());
  const auto state = [](hal::CanBusState s) { return static_cast<std::int32_t>(s); };
  // Error warning, then error passive: events, the arm keeps working.
  std::array<std::uint8_t, 8> crtl{};
  crtl[1] = CAN_ERR_CRTL_TX_WARNING;
  rig.bus.inject_error_frame(*rig.master_port, CAN_ERR_CRTL, crtl);
  rig.until([&] { return false; }, 3);
  EXPECT_TRUE(has_event_with(rig, EventId::ARM_CAN_BUS, state(hal::CanBusState::error_warning), 0));
  crtl[1] = CAN_ERR_CRTL_TX_PASSIVE;
  rig.bus.inject_error_frame(*rig.master_port, CAN_ERR_CRTL, crtl);
  rig.until([&] { return false; }, 3);
  EXPECT_TRUE(has_event_with(rig, EventId::ARM_CAN_BUS, state(hal::CanBusState::error_passive), 0));
  EXPECT_EQ(rig.h.exec().mode(), Mode::IDLE);
  const auto stow = rig.h.make(FunctionCode::ARM_STOW);
  rig.h.send(stow);
  ASSERT_TRUE(rig.until([&] { return rig.h.has_ack(stow.counter, AckStage::COMPLETED); }, 4000));
  // Bus-off: the arm cannot be commanded any more.
  cmd::Command go;
  start_motion(rig, go);
  rig.bus.inject_error_frame(*rig.master_port, CAN_ERR_BUSOFF);
  ASSERT_TRUE(rig.until([&] { return rig.h.exec().mode() == Mode::SAFE; }, 20));
  EXPECT_TRUE(has_event_with(rig, EventId::ARM_CAN_BUS, state(hal::CanBusState::bus_off), 0));
  EXPECT_TRUE(rig.h.has_ack(go.counter, AckStage::FAILED));
  // The controller restarts; leaving SAFE reboots the drives.
  rig.bus.inject_error_frame(*rig.master_port, CAN_ERR_RESTARTED);
  rig.until([&] { return false; }, 40);  // heartbeats lost during bus-off are noticed first
  cmd::SetModeArgs idle;
  idle.mode = static_cast<std::uint8_t>(Mode::IDLE);
  const auto leave = rig.h.make(FunctionCode::SET_MODE, idle);
  rig.h.send(leave);
  ASSERT_TRUE(rig.until([&] { return rig.h.has_ack(leave.counter, AckStage::COMPLETED); }, 50));
  ASSERT_TRUE(rig.until([&] { return count_events(rig, EventId::ARM_READY) == 2; }, 500));
}

TEST(ExecutiveArmFaults, AMalformedFrameIsReportedAndIgnored) {
  ArmRig rig;
  ASSERT_TRUE(rig.boot());
  auto intruder = rig.bus.attach();
  ASSERT_TRUE(intruder.ok());
  hal::CanFrame bad;
  bad.id = 0x183;  // node 3's TPDO1 must carry 6 bytes
  bad.len = 3;
  ASSERT_TRUE((*intruder)->send(bad).ok());
  rig.until([&] { return false; }, 5);
  EXPECT_TRUE(has_event_with(rig, EventId::ARM_BAD_FRAME, 3, 0x183));
  EXPECT_EQ(rig.h.exec().mode(), Mode::IDLE);
  const auto stow = rig.h.make(FunctionCode::ARM_STOW);
  rig.h.send(stow);
  ASSERT_TRUE(rig.until([&] { return rig.h.has_ack(stow.counter, AckStage::COMPLETED); }, 4000));
}

}  // namespace
}  // namespace petra
