// Every check of the command validator, one reason each, on real signed packets.
#include "cmd/validator.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "algo/wire/crc16.hpp"
#include "cmd/command_packet.hpp"
#include "cmd/param_defs.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra::cmd {
namespace {

AuthKey test_key(std::uint8_t seed = 7) {
  AuthKey k;
  for (std::size_t i = 0; i < k.bytes.size(); ++i) k.bytes[i] = static_cast<std::uint8_t>(seed + i);
  return k;
}

std::vector<std::uint8_t> packet(const Command& c, const AuthKey& key = test_key()) {
  std::vector<std::uint8_t> out(kMaxCommandBytes);
  auto n = encode_command_packet(c, 1, key, out);
  EXPECT_TRUE(n.ok());
  out.resize(n.ok() ? *n : 0);
  return out;
}

Command roi_command(std::uint32_t counter) {
  SelectRoiArgs a;
  a.x_px = 100;
  a.y_px = 50;
  a.w_px = 200;
  a.h_px = 150;
  a.planes = 3;
  a.has_click = 1;
  a.click_u_px = 180;
  a.click_v_px = 120;
  return Command{FunctionCode::SELECT_ROI, counter, a};
}

void refresh_crc(std::vector<std::uint8_t>& p) {
  const std::uint16_t crc = wire::crc16_ccitt(std::span(p).first(p.size() - 2));
  p[p.size() - 2] = static_cast<std::uint8_t>(crc >> 8);
  p[p.size() - 1] = static_cast<std::uint8_t>(crc);
}

class Validator : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(auth_init().ok()); }
  ValidationContext ctx() {
    ValidationContext c;
    c.key = &key_;
    c.last_counter = 10;
    c.mode = Mode::IDLE;
    c.image_width = 640;
    c.image_height = 480;
    return c;
  }
  AuthKey key_ = test_key();
};

TEST_F(Validator, AcceptsAValidSignedCommandAndDecodesItsArguments) {
  const Verdict v = validate_command(packet(roi_command(11)), ctx());
  ASSERT_TRUE(v.ok()) << reason_name(v.reason);
  EXPECT_TRUE(v.authenticated);
  EXPECT_EQ(v.command.counter, 11u);
  const auto* a = std::get_if<SelectRoiArgs>(&v.command.args);
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->x_px, 100);
  EXPECT_EQ(a->h_px, 150);
  EXPECT_EQ(a->planes, 3);
  EXPECT_EQ(a->click_v_px, 120);
}

TEST_F(Validator, EveryCommandRoundTripsWithDefaultArguments) {
  std::uint32_t counter = 11;
  ValidationContext c = ctx();
  for (const CommandDesc& d : command_table()) {
    Command cmd{static_cast<FunctionCode>(d.code), counter++,
                default_args(static_cast<FunctionCode>(d.code))};
    const auto p = packet(cmd);
    EXPECT_EQ(p.size(), kTcOverheadBytes + d.arg_bytes) << d.name;
    const Verdict v = validate_command(p, c);
    // Defaults may be out of range (e.g. ROI 0x0); the frame checks must all pass.
    EXPECT_TRUE(v.authenticated) << d.name << " " << reason_name(v.reason);
    EXPECT_EQ(v.function_code, d.code);
  }
}

TEST_F(Validator, TruncatedIsTooShortOrLengthMismatch) {
  auto p = packet(roi_command(11));
  EXPECT_EQ(validate_command(std::span(p).first(5), ctx()).reason, Reason::TOO_SHORT);
  EXPECT_EQ(validate_command(std::span(p).first(kMinCommandBytes - 1), ctx()).reason,
            Reason::TOO_SHORT);
  EXPECT_EQ(validate_command(std::span(p).first(p.size() - 1), ctx()).reason,
            Reason::LENGTH_MISMATCH);
}

TEST_F(Validator, OversizeIsTooLong) {
  std::vector<std::uint8_t> p(kMaxCommandBytes + 1, 0);
  EXPECT_EQ(validate_command(p, ctx()).reason, Reason::TOO_LONG);
}

TEST_F(Validator, WrongPacketTypeOrApidIsBadHeader) {
  auto p = packet(roi_command(11));
  auto q = p;
  q[0] &= 0xEF;  // type bit -> telemetry
  EXPECT_EQ(validate_command(q, ctx()).reason, Reason::BAD_HEADER);
  q = p;
  q[1] ^= 0x01;  // APID
  EXPECT_EQ(validate_command(q, ctx()).reason, Reason::BAD_HEADER);
}

TEST_F(Validator, AnyCorruptedByteIsBadCrc) {
  const auto p = packet(roi_command(11));
  for (std::size_t i = 8; i < p.size(); ++i) {
    auto q = p;
    q[i] ^= 0x40;
    EXPECT_EQ(validate_command(q, ctx()).reason, Reason::BAD_CRC) << "byte " << i;
  }
}

TEST_F(Validator, ForgedMacOrOtherKeyIsBadAuth) {
  auto p = packet(roi_command(11), test_key(99));  // signed with another key
  EXPECT_EQ(validate_command(p, ctx()).reason, Reason::BAD_AUTH);
  p = packet(roi_command(11));
  p[14] ^= 0x01;  // change an argument, keep the CRC right: the MAC no longer matches
  refresh_crc(p);
  const Verdict v = validate_command(p, ctx());
  EXPECT_EQ(v.reason, Reason::BAD_AUTH);
  EXPECT_FALSE(v.authenticated);
}

TEST_F(Validator, ReplayedOrStaleCounterIsReplay) {
  ValidationContext c = ctx();
  EXPECT_EQ(validate_command(packet(roi_command(10)), c).reason, Reason::REPLAY);
  EXPECT_EQ(validate_command(packet(roi_command(3)), c).reason, Reason::REPLAY);
  EXPECT_FALSE(validate_command(packet(roi_command(3)), c).authenticated);
}

TEST_F(Validator, UnknownFunctionCodeIsRejectedAfterAuthentication) {
  auto p = packet(Command{FunctionCode::NOOP, 11, NoopArgs{}});
  p[6] = 0x7E;
  // re-sign so only the function code is wrong
  const Mac mac = compute_mac(key_, std::span(p).first(kTcHeaderBytes));
  std::copy(mac.begin(), mac.end(), p.begin() + kTcHeaderBytes);
  refresh_crc(p);
  const Verdict v = validate_command(p, ctx());
  EXPECT_EQ(v.reason, Reason::UNKNOWN_FUNCTION);
  EXPECT_EQ(v.detail, 0x7E);
  EXPECT_TRUE(v.authenticated);
}

TEST_F(Validator, ArgumentsOfAnotherCommandAreBadPayloadLength) {
  // NOOP's function code with SELECT_ROI's arguments, correctly signed.
  auto p = packet(roi_command(11));
  p[6] = static_cast<std::uint8_t>(FunctionCode::NOOP);
  const std::size_t mac_at = p.size() - kCrcBytes - kHmacBytes;
  const Mac mac = compute_mac(key_, std::span(p).first(mac_at));
  std::copy(mac.begin(), mac.end(), p.begin() + static_cast<long>(mac_at));
  refresh_crc(p);
  EXPECT_EQ(validate_command(p, ctx()).reason, Reason::BAD_PAYLOAD_LENGTH);
}

TEST_F(Validator, OutOfRangeNamesTheField) {
  Command c = roi_command(11);
  std::get<SelectRoiArgs>(c.args).planes = 9;  // c in 1..8
  Verdict v = validate_command(packet(c), ctx());
  EXPECT_EQ(v.reason, Reason::OUT_OF_RANGE);
  EXPECT_EQ(v.detail, 4);  // field index of `planes`
  ArmGotoArgs g;
  g.standoff_mm = std::numeric_limits<float>::quiet_NaN();
  v = validate_command(packet(Command{FunctionCode::ARM_GOTO, 11, g}), ctx());
  EXPECT_EQ(v.reason, Reason::OUT_OF_RANGE);
  EXPECT_EQ(v.detail, 1);
}

TEST_F(Validator, InconsistentArgumentsAreInvalid) {
  Command c = roi_command(11);
  std::get<SelectRoiArgs>(c.args).x_px = 500;  // 500 + 200 > 640
  EXPECT_EQ(validate_command(packet(c), ctx()).reason, Reason::INVALID_ARGUMENT);
  c = roi_command(11);
  std::get<SelectRoiArgs>(c.args).click_u_px = 20;  // left of the ROI
  const Verdict v = validate_command(packet(c), ctx());
  EXPECT_EQ(v.reason, Reason::INVALID_ARGUMENT);
  EXPECT_EQ(v.detail, 6);
  GetParamArgs g;
  g.param_id = 999;
  EXPECT_EQ(validate_command(packet(Command{FunctionCode::GET_PARAM, 11, g}), ctx()).reason,
            Reason::INVALID_ARGUMENT);
  SetParamArgs s;
  s.param_id = static_cast<std::uint16_t>(ParamId::THUMB_DECIMATION);
  s.value = 2.5;  // must be whole
  EXPECT_EQ(validate_command(packet(Command{FunctionCode::SET_PARAM, 11, s}), ctx()).reason,
            Reason::OUT_OF_RANGE);
}

// The memory budget fixed at boot: an ROI or envelope beyond it is refused
// with the limit as detail; within it (or with no budget) it passes.
TEST_F(Validator, BeyondTheMemoryBudgetIsRefusedWithTheLimit) {
  ValidationContext c = ctx();
  c.max_roi_width = 199;
  c.max_roi_height = 150;
  c.max_disparities = 257;
  c.disp_min_px = 64;
  c.disp_max_px = 320;
  Verdict v = validate_command(packet(roi_command(11)), c);  // 200 x 150
  EXPECT_EQ(v.reason, Reason::ROI_TOO_WIDE);
  EXPECT_EQ(v.detail, 199);
  c.max_roi_width = 200;
  c.max_roi_height = 149;
  v = validate_command(packet(roi_command(11)), c);
  EXPECT_EQ(v.reason, Reason::ROI_TOO_TALL);
  EXPECT_EQ(v.detail, 149);
  c.max_roi_height = 150;
  EXPECT_TRUE(validate_command(packet(roi_command(11)), c).ok());

  SetParamArgs s;
  s.param_id = static_cast<std::uint16_t>(ParamId::DISP_MAX_PX);
  s.value = 321;  // 64..321: 258 disparities
  v = validate_command(packet(Command{FunctionCode::SET_PARAM, 11, s}), c);
  EXPECT_EQ(v.reason, Reason::ENVELOPE_TOO_WIDE);
  EXPECT_EQ(v.detail, 257);
  s.value = 320;
  EXPECT_TRUE(validate_command(packet(Command{FunctionCode::SET_PARAM, 11, s}), c).ok());
  s.param_id = static_cast<std::uint16_t>(ParamId::DISP_MIN_PX);
  s.value = 63;
  EXPECT_EQ(validate_command(packet(Command{FunctionCode::SET_PARAM, 11, s}), c).reason,
            Reason::ENVELOPE_TOO_WIDE);
  s.value = 100;  // narrower: fine
  EXPECT_TRUE(validate_command(packet(Command{FunctionCode::SET_PARAM, 11, s}), c).ok());
  c.max_disparities = 0;  // no budget: any envelope
  s.value = 0;
  EXPECT_TRUE(validate_command(packet(Command{FunctionCode::SET_PARAM, 11, s}), c).ok());
}

TEST_F(Validator, CommandsOutsideTheirModesAreWrongMode) {
  ValidationContext c = ctx();
  c.mode = Mode::SAFE;
  Verdict v = validate_command(packet(roi_command(11)), c);
  EXPECT_EQ(v.reason, Reason::WRONG_MODE);
  EXPECT_EQ(v.detail, static_cast<std::uint16_t>(Mode::SAFE));
  c.mode = Mode::EVALUATE;
  EXPECT_EQ(validate_command(packet(Command{FunctionCode::ACQUIRE, 11, AcquireArgs{}}), c).reason,
            Reason::WRONG_MODE);
  EXPECT_TRUE(validate_command(packet(Command{FunctionCode::ABORT, 11, AbortArgs{}}), c).ok());
}

TEST_F(Validator, GroundMayOnlyAskForSafeOrLeaveSafe) {
  SetModeArgs m;
  m.mode = static_cast<std::uint8_t>(Mode::EVALUATE);
  EXPECT_EQ(validate_command(packet(Command{FunctionCode::SET_MODE, 11, m}), ctx()).reason,
            Reason::BAD_TRANSITION);
  m.mode = static_cast<std::uint8_t>(Mode::SAFE);
  EXPECT_TRUE(validate_command(packet(Command{FunctionCode::SET_MODE, 11, m}), ctx()).ok());
}

TEST_F(Validator, ValidationAllocatesNothing) {
  const auto good = packet(roi_command(11));
  auto bad = good;
  bad[20] ^= 1;
  petra::test::HeapScope scope;
  for (int i = 0; i < 100; ++i) {
    EXPECT_TRUE(validate_command(good, ctx()).ok());
    EXPECT_FALSE(validate_command(bad, ctx()).ok());
  }
  EXPECT_EQ(scope.allocations(), 0u);
}

}  // namespace
}  // namespace petra::cmd
