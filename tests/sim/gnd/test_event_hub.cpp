// Pages read the hub from their own threads: each sees every message after
// the last one it saw, in order; a late page gets the kept history; close()
// releases waiting readers.
#include <gtest/gtest.h>

#include <thread>

#include "sim/gnd/event_hub.hpp"

namespace petra::gnd {
namespace {

TEST(EventHub, ReadersSeeMessagesInOrderAfterTheirLast) {
  EventHub hub(3);
  hub.publish("tlm", "{\"n\":1}");
  hub.publish("tlm", "{\"n\":2}");
  auto all = hub.wait_after(0, 0);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].seq, 1u);
  EXPECT_EQ(all[1].json, "{\"n\":2}");
  EXPECT_TRUE(hub.wait_after(2, 0).empty());
  hub.publish("sent", "{}");
  hub.publish("sent", "{}");
  auto kept = hub.wait_after(0, 0);  // only the last 3 are kept
  ASSERT_EQ(kept.size(), 3u);
  EXPECT_EQ(kept.front().seq, 2u);
}

TEST(EventHub, WaitingReaderWakesOnPublishAndOnClose) {
  EventHub hub;
  std::thread writer([&] { hub.publish("tlm", "x"); });
  auto got = hub.wait_after(0, 5000);
  writer.join();
  ASSERT_EQ(got.size(), 1u);
  std::thread closer([&] { hub.close(); });
  EXPECT_TRUE(hub.wait_after(1, 60000).empty());  // returns on close, not after a minute
  closer.join();
  EXPECT_TRUE(hub.closed());
}

}  // namespace
}  // namespace petra::gnd
