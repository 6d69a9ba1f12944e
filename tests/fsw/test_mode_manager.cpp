#include "fsw/mode_manager.hpp"

#include <gtest/gtest.h>

namespace petra::fsw {
namespace {

TEST(ModeManager, TransitionTableMatchesTheExecutiveDoc) {
  // from \ to: BOOT IDLE ACQUIRE EVALUATE ARM_MOVING SAFE
  const bool table[6][6] = {
      {0, 1, 0, 0, 0, 1},  // BOOT
      {0, 0, 1, 1, 1, 1},  // IDLE
      {0, 1, 0, 0, 0, 1},  // ACQUIRE
      {0, 1, 0, 0, 0, 1},  // EVALUATE
      {0, 1, 0, 0, 0, 1},  // ARM_MOVING
      {0, 1, 0, 0, 0, 0},  // SAFE
  };
  for (int f = 0; f < 6; ++f)
    for (int t = 0; t < 6; ++t)
      EXPECT_EQ(ModeManager::allowed(static_cast<Mode>(f), static_cast<Mode>(t)), table[f][t])
          << mode_name(static_cast<Mode>(f)) << " -> " << mode_name(static_cast<Mode>(t));
}

TEST(ModeManager, RefusedChangeChangesNothingAndRaisesNoEvent) {
  hal::SystemClock clock;
  std::vector<std::uint8_t> storage(tlm::TlmQueue::bytes_for(8));
  std::vector<std::uint16_t> lengths(8);
  tlm::TlmQueue q;
  q.init(storage, lengths);
  EventLog events;
  events.init(&q, &clock);
  ModeManager m;
  m.init(&events);
  EXPECT_TRUE(m.request(Mode::IDLE, 0));
  EXPECT_EQ(events.total(), 1u);
  EXPECT_FALSE(m.request(Mode::BOOT, 0));
  EXPECT_FALSE(m.request(Mode::IDLE, 0));
  EXPECT_EQ(m.mode(), Mode::IDLE);
  EXPECT_EQ(events.total(), 1u);
  EXPECT_TRUE(m.request(Mode::SAFE, 0x31));
  EXPECT_EQ(events.latest()->args[0], static_cast<int>(Mode::IDLE));
  EXPECT_EQ(events.latest()->args[1], static_cast<int>(Mode::SAFE));
  EXPECT_EQ(events.latest()->args[2], 0x31);
}

}  // namespace
}  // namespace petra::fsw
