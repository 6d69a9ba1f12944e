// libFuzzer target over the telecommand decoder and its authentication
// (cmd/validator), plus the telemetry decoder. Two ways in:
//  - raw: the input is a datagram, validated as received from the network;
//  - signed: the input (after a leading 0x01) is function code + counter +
//    arguments, wrapped in a correct header, HMAC and CRC with the fuzzing key,
//    so the fuzzer reaches argument decoding, ranges, consistency and modes.
// Properties: no crash or sanitizer report; an accepted command has in-range
// arguments and re-encodes to exactly the bytes that were accepted.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>

#include "algo/wire/ccsds.hpp"
#include "algo/wire/crc16.hpp"
#include "cmd/command_packet.hpp"
#include "cmd/validator.hpp"
#include "tlm/telemetry.hpp"

namespace {

petra::cmd::AuthKey fuzz_key() {
  petra::cmd::AuthKey k;
  for (std::size_t i = 0; i < k.bytes.size(); ++i) k.bytes[i] = static_cast<std::uint8_t>(0xA0 + i);
  return k;
}

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz property violated: %s\n", what);
    std::abort();
  }
}

void validate_and_check(std::span<const std::uint8_t> datagram, const petra::cmd::AuthKey& key,
                        std::uint8_t mode_byte) {
  using namespace petra;
  cmd::ValidationContext ctx;
  ctx.key = &key;
  ctx.last_counter = 1000;
  ctx.mode = static_cast<Mode>(1 + mode_byte % 5);  // IDLE..SAFE
  ctx.image_width = 1024;
  ctx.image_height = 768;
  const cmd::Verdict v = cmd::validate_command(datagram, ctx);
  if (!v.ok()) return;
  check(v.authenticated, "accepted without authentication");
  check(v.command.counter > ctx.last_counter, "accepted a stale counter");
  check(cmd::args_out_of_range(v.command.args) < 0, "accepted an out-of-range argument");
  std::uint8_t again[cmd::kMaxCommandBytes];
  const petra::wire::PrimaryHeader h = petra::wire::read_primary_header(datagram);
  auto n = cmd::encode_command_packet(v.command, h.seq_count, key, again);
  check(n.ok() && *n == datagram.size(), "re-encoded size differs");
  check(std::memcmp(again, datagram.data(), datagram.size()) == 0, "re-encoding differs");
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  return petra::cmd::auth_init().ok() ? 0 : 1;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace petra;
  static const cmd::AuthKey key = fuzz_key();
  const std::span<const std::uint8_t> in(data, size);
  (void)tlm::decode_tm(in);  // the ground decoder must also survive anything
  if (size >= 1 && data[0] == 0x01 && size >= 7 && size <= 7 + cmd::max_arg_bytes()) {
    // Signed path: [0x01][mode][fc][counter x4][args...]
    std::uint8_t p[cmd::kMaxCommandBytes];
    const std::size_t args = size - 7;
    const std::size_t total = cmd::kTcOverheadBytes + args;
    wire::PrimaryHeader h;
    h.type = wire::PacketType::telecommand;
    h.apid = cmd::kCommandApid;
    h.seq_flags = wire::SeqFlags::unsegmented;
    h.data_length = static_cast<std::uint16_t>(total - 7);
    wire::write_primary_header(h, p);
    p[6] = data[2];
    p[7] = 0;
    std::memcpy(p + 8, data + 3, 4);
    std::memcpy(p + 12, data + 7, args);
    const cmd::Mac mac = cmd::compute_mac(key, std::span<const std::uint8_t>(p, 12 + args));
    std::memcpy(p + 12 + args, mac.data(), mac.size());
    const std::uint16_t crc = wire::crc16_ccitt(std::span<const std::uint8_t>(p, total - 2));
    p[total - 2] = static_cast<std::uint8_t>(crc >> 8);
    p[total - 1] = static_cast<std::uint8_t>(crc);
    validate_and_check(std::span<const std::uint8_t>(p, total), key, data[1]);
    return 0;
  }
  validate_and_check(in, key, size > 0 ? data[size - 1] : 0);
  return 0;
}
