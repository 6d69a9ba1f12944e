// libFuzzer target over the CANopen frame decoders (hal/canopen/cia301): what
// the arm's master runs on every frame the drives (or a faulty node) send.
// The input is a sequence of frames: [id hi][id lo][len][8 data bytes].
// Properties: no crash or sanitizer report; a heartbeat on a heartbeat COB-ID
// re-encodes to the same identifier; an SDO or EMCY that decodes, re-encoded,
// decodes again (the EMCY to the same error code).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "hal/canopen/cia301.hpp"

namespace {

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz property violated: %s\n", what);
    std::abort();
  }
}

void decode_all(const petra::hal::CanFrame& f) {
  using namespace petra::canopen;
  std::uint8_t node = 0;
  (void)parse_nmt(f, node);
  // The decoders read payloads; the master routes by COB-ID (split_cob_id).
  const auto c = split_cob_id(f.id);
  if (auto hb = parse_heartbeat(f); hb && c.known && c.function == Function::heartbeat) {
    const auto again = make_heartbeat(c.node, *hb);
    check(again.id == f.id && parse_heartbeat(again).ok(), "a heartbeat does not re-encode");
  }
  for (bool from_server : {false, true})
    if (auto sdo = parse_sdo(f, from_server)) {
      const auto again = from_server ? make_sdo_response(c.node, *sdo) : make_sdo_request(c.node, *sdo);
      auto twice = parse_sdo(again, from_server);
      check(twice.ok(), "a re-encoded SDO does not decode");
    }
  if (auto e = parse_emcy(f)) {
    const auto again = make_emcy(c.node, *e);
    auto twice = parse_emcy(again);
    check(twice.ok() && twice->error_code == e->error_code, "a re-encoded EMCY differs");
  }
  (void)parse_rpdo1(f);
  (void)parse_tpdo1(f);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  for (std::size_t at = 0; at + 3 <= size; at += 11) {
    petra::hal::CanFrame f;
    f.id = static_cast<std::uint32_t>((data[at] << 8) | data[at + 1]) & 0x7FF;
    f.len = data[at + 2] & 0x0F;  // 9..15: a bad length the decoders must refuse
    const std::size_t n = size - at - 3 < 8 ? size - at - 3 : 8;
    std::memcpy(f.data.data(), data + at + 3, n);
    if (f.len > 8) {
      f.len = 8;
      f.rtr = true;  // a remote request: no CANopen decoder takes it
    }
    decode_all(f);
  }
  return 0;
}
