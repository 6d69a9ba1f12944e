#include "hal/canopen/cia402.hpp"

#include <gtest/gtest.h>

namespace petra::canopen {
namespace {

TEST(Cia402, StatuswordDecodesEveryStateAndIgnoresOtherBits) {
  struct Case {
    std::uint16_t sw;
    DriveState state;
  };
  // Values as drives report them (bits 4, 7, 9-15 vary and must not matter).
  const Case cases[] = {
      {0x0000, DriveState::not_ready_to_switch_on},
      {0x0250, DriveState::switch_on_disabled},
      {0x0231, DriveState::ready_to_switch_on},
      {0x0233, DriveState::switched_on},
      {0x0237, DriveState::operation_enabled},
      {0x1637, DriveState::operation_enabled},
      {0x0217, DriveState::quick_stop_active},
      {0x021F, DriveState::fault_reaction_active},
      {0x0218, DriveState::fault},
      {0x2238, DriveState::fault},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(decode_statusword(c.sw), c.state) << std::hex << c.sw;
    EXPECT_EQ(decode_statusword(statusword_bits(c.state)), c.state);
  }
}

TEST(Cia402, ControlwordCommands) {
  EXPECT_EQ(decode_controlword(0x0006), DriveCommand::shutdown);
  EXPECT_EQ(decode_controlword(0x0007), DriveCommand::switch_on);
  EXPECT_EQ(decode_controlword(0x000F), DriveCommand::enable_operation);
  EXPECT_EQ(decode_controlword(0x003F), DriveCommand::enable_operation);  // + pp bits 4, 5
  EXPECT_EQ(decode_controlword(0x0002), DriveCommand::quick_stop);
  EXPECT_EQ(decode_controlword(0x000B), DriveCommand::quick_stop);
  EXPECT_EQ(decode_controlword(0x0000), DriveCommand::disable_voltage);
  EXPECT_EQ(decode_controlword(0x0080), DriveCommand::fault_reset);
}

TEST(Cia402, TheStateMachineWalksToOperationEnabledAndQuickStops) {
  DriveState s = DriveState::switch_on_disabled;
  s = next_drive_state(s, DriveCommand::switch_on, 6);  // not allowed from here
  EXPECT_EQ(s, DriveState::switch_on_disabled);
  s = next_drive_state(s, DriveCommand::shutdown, 6);
  EXPECT_EQ(s, DriveState::ready_to_switch_on);
  s = next_drive_state(s, DriveCommand::switch_on, 6);
  EXPECT_EQ(s, DriveState::switched_on);
  s = next_drive_state(s, DriveCommand::enable_operation, 6);
  EXPECT_EQ(s, DriveState::operation_enabled);
  s = next_drive_state(s, DriveCommand::quick_stop, 6);
  EXPECT_EQ(s, DriveState::quick_stop_active);
  // Option 6 holds; enable operation resumes.
  EXPECT_EQ(next_drive_state(s, DriveCommand::shutdown, 6), DriveState::quick_stop_active);
  EXPECT_EQ(next_drive_state(s, DriveCommand::enable_operation, 6), DriveState::operation_enabled);
  EXPECT_EQ(next_drive_state(s, DriveCommand::disable_voltage, 6), DriveState::switch_on_disabled);
  // Fault leaves only by a fault reset.
  EXPECT_EQ(next_drive_state(DriveState::fault, DriveCommand::enable_operation, 6),
            DriveState::fault);
  EXPECT_EQ(next_drive_state(DriveState::fault, DriveCommand::fault_reset, 6),
            DriveState::switch_on_disabled);
}

}  // namespace
}  // namespace petra::canopen
