#include "hal/udp_can.hpp"

#include <gtest/gtest.h>

#include <array>

#include "tests/support/heap_counter.hpp"

namespace petra::hal {
namespace {

std::uint16_t free_port() {
  UdpLink l;
  if (!l.open("127.0.0.1", 0)) return 0;
  return l.local_port();
}

TEST(UdpCanSpec, ParsesPortsAndRejectsMalformedNames) {
  auto s = parse_udp_can_spec("udp:47001:47002");
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->local_port, 47001);
  EXPECT_EQ(s->peer_port, 47002);
  EXPECT_TRUE(is_udp_can_spec("udp:1:2"));
  EXPECT_FALSE(is_udp_can_spec("can0"));
  for (const char* bad : {"udp:", "udp:1", "udp:1:", "udp:0:5", "udp:5:0", "udp:70000:5",
                          "udp:5:6x", "udp:a:b", "udp::5", "can0"}) {
    auto r = parse_udp_can_spec(bad);
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_EQ(r.code(), Errc::parse_error) << bad;
    EXPECT_NE(std::string(r.error().message).find("udp:LOCAL_PORT:PEER_PORT"), std::string::npos);
  }
}

TEST(UdpCanCodec, RoundTripsStandardExtendedAndRemoteFrames) {
  CanFrame a;
  a.id = 0x601;
  a.len = 8;
  a.data = {0x40, 0x00, 0x10, 0x00, 1, 2, 3, 4};
  CanFrame b;
  b.id = 0x1ABCDEF0;
  b.extended = true;
  b.len = 3;
  b.data = {9, 8, 7};
  CanFrame c;
  c.id = 0x700;
  c.rtr = true;
  for (const CanFrame& f : {a, b, c}) {
    std::array<std::uint8_t, kUdpCanDatagramBytes> d{};
    encode_udp_can(f, d);
    auto back = decode_udp_can(d);
    ASSERT_TRUE(back.ok());
    EXPECT_EQ(back->id, f.id);
    EXPECT_EQ(back->extended, f.extended);
    EXPECT_EQ(back->rtr, f.rtr);
    EXPECT_EQ(back->len, f.len);
    EXPECT_EQ(back->data, f.data);
  }
  std::array<std::uint8_t, kUdpCanDatagramBytes> d{};
  encode_udp_can(a, d);
  EXPECT_EQ(d[0], 0x01);  // little-endian id
  EXPECT_EQ(d[1], 0x06);
  EXPECT_EQ(d[4], 8);
}

TEST(UdpCanCodec, RejectsMalformedDatagramsNamingTheProblem) {
  std::array<std::uint8_t, kUdpCanDatagramBytes> good{};
  CanFrame f;
  f.id = 0x181;
  f.len = 6;
  encode_udp_can(f, good);
  auto short_one = decode_udp_can(std::span<const std::uint8_t>(good.data(), 15));
  ASSERT_FALSE(short_one.ok());
  EXPECT_NE(std::string(short_one.error().message).find("15 bytes"), std::string::npos);
  auto d = good;
  d[4] = 9;  // length over 8
  EXPECT_FALSE(decode_udp_can(d).ok());
  d = good;
  d[6] = 1;  // reserved
  EXPECT_NE(std::string(decode_udp_can(d).error().message).find("reserved"), std::string::npos);
  d = good;
  d[1] = 0x08;  // standard id 0x881: wider than 11 bits
  EXPECT_FALSE(decode_udp_can(d).ok());
  d = good;
  d[3] = 0x20;  // error-frame flag
  EXPECT_FALSE(decode_udp_can(d).ok());
}

TEST(UdpCanPort, TwoPortsExchangeFramesInOrderWithoutHeap) {
  const std::uint16_t pa = free_port(), pb = free_port();
  ASSERT_NE(pa, 0);
  ASSERT_NE(pb, 0);
  UdpCanPort a, b;
  ASSERT_TRUE(a.open({pa, pb}).ok());
  ASSERT_TRUE(b.open({pb, pa}).ok());
  CanFrame f;
  f.len = 2;
  {
    test::HeapScope scope;
    for (std::uint32_t k = 0; k < 50; ++k) {
      f.id = 0x180 + k;
      f.data[0] = static_cast<std::uint8_t>(k);
      ASSERT_TRUE(a.send(f).ok());
    }
    for (std::uint32_t k = 0; k < 50; ++k) {
      CanFrame got;
      auto r = b.receive(got, 200);
      ASSERT_TRUE(r.ok() && *r) << k;
      EXPECT_EQ(got.id, 0x180 + k);
      EXPECT_EQ(got.data[0], k);
    }
    CanFrame none;
    auto r = b.receive(none, 0);
    ASSERT_TRUE(r.ok());
    EXPECT_FALSE(*r);
    EXPECT_EQ(scope.allocations(), 0u);
  }
  EXPECT_EQ(a.health().frames_sent, 50u);
  EXPECT_EQ(b.health().frames_received, 50u);
  CanFrame bad;
  bad.id = 0x800;  // 12 bits, standard: refused before it leaves
  EXPECT_EQ(a.send(bad).code(), Errc::invalid_argument);
}

TEST(UdpCanPort, AMalformedDatagramIsCountedAndSkipped) {
  const std::uint16_t pa = free_port(), pb = free_port();
  UdpCanPort b;
  ASSERT_TRUE(b.open({pb, pa}).ok());
  UdpLink raw;
  ASSERT_TRUE(raw.open("127.0.0.1", pa).ok());
  ASSERT_TRUE(raw.set_peer("127.0.0.1", pb).ok());
  const std::array<std::uint8_t, 5> junk{1, 2, 3, 4, 5};
  ASSERT_EQ(raw.send(junk), SendResult::sent);
  CanFrame f;
  f.id = 0x701;
  f.len = 1;
  f.data[0] = 5;
  std::array<std::uint8_t, kUdpCanDatagramBytes> d{};
  encode_udp_can(f, d);
  ASSERT_EQ(raw.send(d), SendResult::sent);
  CanFrame got;
  auto r = b.receive(got, 200);
  ASSERT_TRUE(r.ok() && *r);
  EXPECT_EQ(got.id, 0x701u);
  EXPECT_EQ(b.health().rx_dropped, 1u);
  EXPECT_EQ(b.health().frames_received, 1u);
}

TEST(UdpCanPort, AnEmptyDatagramIsCountedAndDoesNotEndTheWait) {
  const std::uint16_t pa = free_port(), pb = free_port();
  UdpCanPort b;
  ASSERT_TRUE(b.open({pb, pa}).ok());
  UdpLink raw;
  ASSERT_TRUE(raw.open("127.0.0.1", pa).ok());
  ASSERT_TRUE(raw.set_peer("127.0.0.1", pb).ok());
  ASSERT_EQ(raw.send({}), SendResult::sent);
  CanFrame f;
  f.id = 0x702;
  f.len = 1;
  std::array<std::uint8_t, kUdpCanDatagramBytes> d{};
  encode_udp_can(f, d);
  ASSERT_EQ(raw.send(d), SendResult::sent);
  CanFrame got;
  auto r = b.receive(got, 200);
  ASSERT_TRUE(r.ok() && *r);
  EXPECT_EQ(got.id, 0x702u);
  EXPECT_EQ(b.health().rx_dropped, 1u);
}

}  // namespace
}  // namespace petra::hal
