// The PROPOSALS packet: a full list round trips through the codec field by
// field, and the packet stays within the downlink's largest packet (PRODUCT),
// as PROPOSAL_PLANES does.
#include <gtest/gtest.h>

#include <vector>

#include "tlm/telemetry.hpp"

namespace petra::tlm {
namespace {

// Every slot filled with values that differ per slot and per field.
Proposals full_list() {
  Proposals p;
  p.proposal_id = 0x01020304;
  p.frame = 77;
  p.status = 1;
  p.reason = 0;
  p.empty_reason = 4;
  p.count = PETRA_MAX_PROPOSALS;
  p.candidates = 513;
  p.region_px = {16, 32, 992, 704};
  p.total_ms = 812;
  p.picture_step = 4;
  for (std::size_t i = 0; i < PETRA_MAX_PROPOSALS; ++i) {
    const auto k = static_cast<float>(i);
    p.rank[i] = static_cast<std::uint8_t>(i + 1);
    for (std::size_t c = 0; c < 4; ++c)
      p.roi_px[4 * i + c] = static_cast<std::uint16_t>(100 * i + c);
    p.click_px[2 * i] = static_cast<std::uint16_t>(8191 - i);
    p.click_px[2 * i + 1] = static_cast<std::uint16_t>(i);
    p.height_mm[i] = 10.5f + k;
    p.size_mm[i] = 120.25f + k;
    p.planes_c[i] = static_cast<std::uint8_t>(1 + i % 8);
    p.note[i] = static_cast<std::uint8_t>(i % 4);
    p.plane_count[i] = static_cast<std::uint8_t>(i % 4);
    p.plane_offered[i] = static_cast<std::uint8_t>(i % 2);
    p.score_total[i] = 1.0f - 0.1f * k;
    p.score_grindable[i] = 0.125f * k;
    p.score_reach[i] = 0.5f;
    p.score_certainty[i] = 0.0625f * k;
    p.score_size[i] = 1.0f;
    for (std::size_t c = 0; c < 3; ++c) {
      p.normal[3 * i + c] = c == 2 ? -0.8f : 0.1f * k - 0.4f;
      p.centroid_mm[3 * i + c] = -250.125f + 17.5f * k + static_cast<float>(c);
    }
    p.area_mm2[i] = 1530.5f + k;
    p.normal_sigma_deg[i] = 0.25f * k;
    p.offset_sigma_mm[i] = 0.125f * k;
    p.verdict[i] = static_cast<std::uint8_t>(i % 7);
    p.reach[i] = static_cast<std::uint8_t>(6 - i % 7);
  }
  return p;
}

TEST(ProposalsPacket, AFullListRoundTripsFieldByField) {
  const Proposals p = full_list();
  ASSERT_EQ(p.out_of_range(), -1);
  std::vector<std::uint8_t> buf(kMaxTmBytes);
  const std::size_t n = encode_tm(p, 9, wire::SeqFlags::unsegmented, TmTime{1800000000, 5}, buf);
  ASSERT_EQ(n, kTmHeaderBytes + Proposals::wire_bytes() + kTmCrcBytes);
  auto d = decode_tm(std::span(buf).first(n));
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_EQ(d->header.primary.apid, static_cast<std::uint16_t>(Apid::PROPOSALS));
  const auto& q = std::get<Proposals>(d->body);
  // Every field compared by name, in wire order.
  std::vector<std::string> names;
  p.each([&](const char* name, const auto& want) {
    names.push_back(name);
    q.each([&](const char* other, const auto& got) {
      if constexpr (std::is_same_v<decltype(want), decltype(got)>) {
        if (std::string(name) == other) {
          EXPECT_EQ(got, want) << name;
        }
      }
    });
  });
  EXPECT_EQ(names.size(), Proposals::fields().size());
}

TEST(ProposalsPacket, FitsWithinTheLargestPacketAndChecksItsRanges) {
  // 691 payload bytes (27 + 8 x 83): within PRODUCT's (the downlink's buffers and queue slots).
  EXPECT_EQ(Proposals::wire_bytes(), 691u);
  EXPECT_LE(Proposals::wire_bytes(), Product::wire_bytes());
  Proposals p = full_list();
  p.score_total[3] = 1.5f;  // a score is in [0, 1]
  const int bad = p.out_of_range();
  ASSERT_GE(bad, 0);
  EXPECT_STREQ(Proposals::fields()[static_cast<std::size_t>(bad)].name, "score_total");
}

TEST(ProposalsPacket, ProposalPlanesFitOneDatagram) {
  // 1265 payload bytes (9 + 32 planes x 39 + 8 plane counts), the largest
  // packet: with its headers within one 1500-byte Ethernet frame's UDP payload.
  EXPECT_EQ(ProposalPlanes::wire_bytes(), 1265u);
  EXPECT_EQ(kMaxTmBytes, 1281u);
  EXPECT_LE(kMaxTmBytes, 1472u);
  ProposalPlanes p;
  p.plane_count[5] = 5;  // a proposal carries at most 4 planes
  const int bad = p.out_of_range();
  ASSERT_GE(bad, 0);
  EXPECT_STREQ(ProposalPlanes::fields()[static_cast<std::size_t>(bad)].name, "plane_count");
}

}  // namespace
}  // namespace petra::tlm
