// The CiA 301 codec against byte strings written out by hand from the
// specification (so a shared encode/decode mistake cannot hide).
#include "hal/canopen/cia301.hpp"

#include <gtest/gtest.h>

#include <array>

namespace petra::canopen {
namespace {

using Bytes = std::array<std::uint8_t, 8>;

void expect_frame(const CanFrame& f, std::uint32_t id, std::initializer_list<std::uint8_t> bytes) {
  EXPECT_EQ(f.id, id);
  ASSERT_EQ(f.len, bytes.size());
  std::size_t i = 0;
  for (std::uint8_t b : bytes) {
    EXPECT_EQ(f.data[i], b) << "byte " << i;
    ++i;
  }
  EXPECT_FALSE(f.extended);
  EXPECT_FALSE(f.rtr);
}

CanFrame raw(std::uint32_t id, std::initializer_list<std::uint8_t> bytes) {
  CanFrame f;
  f.id = id;
  for (std::uint8_t b : bytes) f.data[f.len++] = b;
  return f;
}

TEST(Cia301, CobIdsOfThePredefinedConnectionSet) {
  EXPECT_EQ(cob_id(Function::tpdo1, 5), 0x185u);
  EXPECT_EQ(cob_id(Function::rpdo1, 5), 0x205u);
  EXPECT_EQ(cob_id(Function::sdo_tx, 5), 0x585u);
  EXPECT_EQ(cob_id(Function::sdo_rx, 5), 0x605u);
  EXPECT_EQ(cob_id(Function::heartbeat, 5), 0x705u);
  EXPECT_EQ(cob_id(Function::emcy, 5), 0x085u);
  const CobId sync = split_cob_id(0x080);
  EXPECT_TRUE(sync.known);
  EXPECT_EQ(sync.function, Function::sync);
  const CobId emcy = split_cob_id(0x081);
  EXPECT_EQ(emcy.function, Function::emcy);
  EXPECT_EQ(emcy.node, 1);
  const CobId hb = split_cob_id(0x77F);
  EXPECT_EQ(hb.function, Function::heartbeat);
  EXPECT_EQ(hb.node, 127);
  EXPECT_FALSE(split_cob_id(0x700).known);  // node 0 is not a node
  EXPECT_FALSE(split_cob_id(0x280).known);  // TPDO2..: not used here
  EXPECT_FALSE(split_cob_id(0x7FF).known);  // function code 15: not in the set
  EXPECT_FALSE(split_cob_id(0x800).known);  // wider than 11 bits
}

TEST(Cia301, NmtAndSyncAndHeartbeat) {
  expect_frame(make_nmt(NmtCommand::start, 5), 0x000, {0x01, 0x05});
  expect_frame(make_nmt(NmtCommand::reset_communication, 0), 0x000, {0x82, 0x00});
  expect_frame(make_sync(), 0x080, {});
  expect_frame(make_heartbeat(5, NmtState::operational), 0x705, {0x05});
  expect_frame(make_heartbeat(3, NmtState::boot_up), 0x703, {0x00});
  std::uint8_t node = 0;
  auto cmd = parse_nmt(raw(0x000, {0x81, 0x07}), node);
  ASSERT_TRUE(cmd.ok());
  EXPECT_EQ(*cmd, NmtCommand::reset_node);
  EXPECT_EQ(node, 7);
  EXPECT_FALSE(parse_nmt(raw(0x000, {0x03, 0x07}), node).ok());  // no such command
  EXPECT_FALSE(parse_nmt(raw(0x000, {0x01}), node).ok());        // short
  EXPECT_FALSE(parse_nmt(raw(0x000, {0x01, 0x80}), node).ok());  // node 128
  auto hb = parse_heartbeat(raw(0x705, {0x7F}));
  ASSERT_TRUE(hb.ok());
  EXPECT_EQ(*hb, NmtState::preoperational);
  EXPECT_EQ(parse_heartbeat(raw(0x705, {0x05, 0x00})).code(), Errc::parse_error);
  EXPECT_EQ(parse_heartbeat(raw(0x705, {0x06})).code(), Errc::parse_error);
  CanFrame ext = raw(0x705, {0x05});
  ext.extended = true;
  EXPECT_FALSE(parse_heartbeat(ext).ok());
}

TEST(Cia301, ExpeditedSdoDownloadsAsTheSpecWritesThem) {
  SdoMessage m{SdoKind::download_request, {0x6040, 0}, 0x000F, 2};
  expect_frame(make_sdo_request(3, m), 0x603, {0x2B, 0x40, 0x60, 0x00, 0x0F, 0x00, 0x00, 0x00});
  m = {SdoKind::download_request, {0x6060, 0}, 0x01, 1};
  expect_frame(make_sdo_request(3, m), 0x603, {0x2F, 0x60, 0x60, 0x00, 0x01, 0x00, 0x00, 0x00});
  m = {SdoKind::download_request, {0x6081, 0}, 0x00012345, 4};
  expect_frame(make_sdo_request(3, m), 0x603, {0x23, 0x81, 0x60, 0x00, 0x45, 0x23, 0x01, 0x00});
  m = {SdoKind::download_request, {0x1600, 1}, 0x607A0020, 4};
  expect_frame(make_sdo_request(1, m), 0x601, {0x23, 0x00, 0x16, 0x01, 0x20, 0x00, 0x7A, 0x60});
  // The server's answer and the client reading it.
  expect_frame(make_sdo_response(3, {SdoKind::download_response, {0x6040, 0}, 0, 0}), 0x583,
               {0x60, 0x40, 0x60, 0x00, 0x00, 0x00, 0x00, 0x00});
  auto r = parse_sdo(raw(0x583, {0x60, 0x40, 0x60, 0x00, 0, 0, 0, 0}), true);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->kind, SdoKind::download_response);
  EXPECT_TRUE(r->address == (SdoAddress{0x6040, 0}));
  // The server reading a request.
  auto q = parse_sdo(raw(0x603, {0x2B, 0x17, 0x10, 0x00, 0x64, 0x00, 0xAA, 0xBB}), false);
  ASSERT_TRUE(q.ok());
  EXPECT_EQ(q->kind, SdoKind::download_request);
  EXPECT_EQ(q->size, 2);
  EXPECT_EQ(q->value, 100u);  // bytes past the stated size are ignored
}

TEST(Cia301, ExpeditedSdoUploadsAndAborts) {
  expect_frame(make_sdo_request(3, {SdoKind::upload_request, {0x1000, 0}, 0, 0}), 0x603,
               {0x40, 0x00, 0x10, 0x00, 0x00, 0x00, 0x00, 0x00});
  auto r = parse_sdo(raw(0x583, {0x43, 0x00, 0x10, 0x00, 0x92, 0x01, 0x02, 0x00}), true);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->kind, SdoKind::upload_response);
  EXPECT_EQ(r->value, 0x00020192u);
  EXPECT_EQ(r->size, 4);
  r = parse_sdo(raw(0x583, {0x4B, 0x41, 0x60, 0x00, 0x37, 0x02, 0xFF, 0xFF}), true);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->value, 0x0237u);
  EXPECT_EQ(r->size, 2);
  r = parse_sdo(raw(0x583, {0x80, 0x00, 0x10, 0x00, 0x00, 0x00, 0x02, 0x06}), true);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->kind, SdoKind::abort);
  EXPECT_EQ(r->value, sdo_abort::kNoObject);
  expect_frame(make_sdo_response(3, {SdoKind::abort, {0x6060, 0}, sdo_abort::kValueRange, 0}),
               0x583, {0x80, 0x60, 0x60, 0x00, 0x30, 0x00, 0x09, 0x06});
  // Segmented upload (0x41) and block transfers are not part of the subset.
  EXPECT_EQ(parse_sdo(raw(0x583, {0x41, 0x08, 0x10, 0x00, 0x10, 0, 0, 0}), true).code(),
            Errc::parse_error);
  EXPECT_EQ(parse_sdo(raw(0x583, {0xC2, 0x08, 0x10, 0x00, 0, 0, 0, 0}), true).code(),
            Errc::parse_error);
  // A client command arriving where a server answer is expected.
  EXPECT_FALSE(parse_sdo(raw(0x583, {0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0}), true).ok());
  EXPECT_FALSE(parse_sdo(raw(0x583, {0x60, 0x40, 0x60, 0x00, 0, 0, 0}), true).ok());  // 7 bytes
}

TEST(Cia301, EmergencyAndPdos) {
  Emergency e;
  e.error_code = 0x8611;
  e.error_register = 0x01;
  expect_frame(make_emcy(2, e), 0x082, {0x11, 0x86, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00});
  auto p = parse_emcy(raw(0x082, {0x10, 0x23, 0x05, 1, 2, 3, 4, 5}));
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->error_code, 0x2310);
  EXPECT_EQ(p->error_register, 0x05);
  EXPECT_EQ(p->vendor[4], 5);
  EXPECT_FALSE(parse_emcy(raw(0x082, {0x10, 0x23, 0x05})).ok());
  expect_frame(make_rpdo1(1, {0x001F, 0x12345678}), 0x201, {0x1F, 0x00, 0x78, 0x56, 0x34, 0x12});
  expect_frame(make_tpdo1(4, {0x1637, -2}), 0x184, {0x37, 0x16, 0xFE, 0xFF, 0xFF, 0xFF});
  auto t = parse_tpdo1(raw(0x184, {0x37, 0x16, 0xFE, 0xFF, 0xFF, 0xFF}));
  ASSERT_TRUE(t.ok());
  EXPECT_EQ(t->statusword, 0x1637);
  EXPECT_EQ(t->position_actual, -2);
  EXPECT_FALSE(parse_tpdo1(raw(0x184, {0x37, 0x16})).ok());  // the power-on layout: statusword only
  auto rp = parse_rpdo1(raw(0x201, {0x1F, 0x00, 0x78, 0x56, 0x34, 0x12}));
  ASSERT_TRUE(rp.ok());
  EXPECT_EQ(rp->target_position, 0x12345678);
}

}  // namespace
}  // namespace petra::canopen
