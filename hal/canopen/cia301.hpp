// CiA 301 (CANopen application layer) subset used by the arm: predefined
// connection set COB-IDs, NMT, heartbeat, expedited SDO, EMCY, and the fixed
// PDO layout Petra programs into every drive. Pure encode/decode of CanFrame;
// no OS calls, no heap. One definition, shared by the master
// (hal/canopen/canopen_master.hpp) and the simulated drive (sim/arm/).
// Byte order on the wire is little-endian (CiA 301).
#pragma once

#include <cstdint>

#include "algo/core/result.hpp"
#include "hal/can.hpp"

namespace petra::canopen {

using hal::CanFrame;

inline constexpr std::uint8_t kMinNodeId = 1;
inline constexpr std::uint8_t kMaxNodeId = 127;
inline bool valid_node_id(unsigned id) {
  return id >= kMinNodeId && id <= kMaxNodeId;
}

// Predefined connection set: COB-ID = function code + node id.
enum class Function : std::uint16_t {
  nmt = 0x000,
  sync = 0x080,
  emcy = 0x080,  // + node id (1..127); 0x080 alone is SYNC
  tpdo1 = 0x180,
  rpdo1 = 0x200,
  sdo_tx = 0x580,  // server (drive) -> client (master)
  sdo_rx = 0x600,  // client (master) -> server (drive)
  heartbeat = 0x700,
};
inline std::uint32_t cob_id(Function f, std::uint8_t node) {
  return static_cast<std::uint32_t>(f) + node;
}

// Splits a received 11-bit COB-ID into function code and node id. SYNC and NMT
// have node 0.
struct CobId {
  Function function = Function::nmt;
  std::uint8_t node = 0;
  bool known = false;  // false: not one of the functions above
};
CobId split_cob_id(std::uint32_t id);

// NMT (CiA 301 7.2.8.3.1).
enum class NmtCommand : std::uint8_t {
  start = 0x01,
  stop = 0x02,
  enter_preoperational = 0x80,
  reset_node = 0x81,
  reset_communication = 0x82,
};
// node 0 addresses every node.
CanFrame make_nmt(NmtCommand command, std::uint8_t node);
Result<NmtCommand> parse_nmt(const CanFrame& frame, std::uint8_t& node);

CanFrame make_sync();

// Heartbeat states (CiA 301 7.2.8.3.2.2).
enum class NmtState : std::uint8_t {
  boot_up = 0x00,
  stopped = 0x04,
  operational = 0x05,
  preoperational = 0x7F,
};
const char* nmt_state_name(NmtState state);
CanFrame make_heartbeat(std::uint8_t node, NmtState state);
// Validates the length (1) and the state byte.
Result<NmtState> parse_heartbeat(const CanFrame& frame);

// Expedited SDO (CiA 301 7.2.4.3): at most 4 data bytes in one frame each way.
struct SdoAddress {
  std::uint16_t index = 0;
  std::uint8_t subindex = 0;
};
inline bool operator==(SdoAddress a, SdoAddress b) {
  return a.index == b.index && a.subindex == b.subindex;
}

enum class SdoKind : std::uint8_t {
  download_request,   // client: write value
  download_response,  // server: written
  upload_request,     // client: read
  upload_response,    // server: value
  abort,              // either side: abort code
};
struct SdoMessage {
  SdoKind kind = SdoKind::abort;
  SdoAddress address;
  std::uint32_t value = 0;  // data (downloads, upload responses) or abort code
  std::uint8_t size = 0;    // data bytes 1..4 (0: not indicated)
};
CanFrame make_sdo_request(std::uint8_t node, const SdoMessage& message);   // to 0x600 + node
CanFrame make_sdo_response(std::uint8_t node, const SdoMessage& message);  // to 0x580 + node
// Parses a frame's 8 data bytes in the client's (`from_server`) or the server's
// view. Segmented and block transfers are refused (Errc::parse_error).
Result<SdoMessage> parse_sdo(const CanFrame& frame, bool from_server);

// Abort codes used (CiA 301 table 22).
namespace sdo_abort {
inline constexpr std::uint32_t kTimeout = 0x05040000;
inline constexpr std::uint32_t kBadCommand = 0x05040001;
inline constexpr std::uint32_t kReadOnly = 0x06010002;
inline constexpr std::uint32_t kWriteOnly = 0x06010001;
inline constexpr std::uint32_t kNoObject = 0x06020000;
inline constexpr std::uint32_t kCannotMap = 0x06040041;
inline constexpr std::uint32_t kLengthMismatch = 0x06070010;
inline constexpr std::uint32_t kNoSubindex = 0x06090011;
inline constexpr std::uint32_t kValueRange = 0x06090030;
inline constexpr std::uint32_t kGeneral = 0x08000000;
inline constexpr std::uint32_t kDeviceState = 0x08000022;
}  // namespace sdo_abort

// Emergency (CiA 301 7.2.7): error code, error register, 5 vendor bytes.
struct Emergency {
  std::uint16_t error_code = 0;  // 0x0000: error reset / no error
  std::uint8_t error_register = 0;
  std::uint8_t vendor[5] = {};
};
CanFrame make_emcy(std::uint8_t node, const Emergency& emcy);
Result<Emergency> parse_emcy(const CanFrame& frame);

// Error codes the arm drives use (CiA 301 table 21, CiA 402 annex).
namespace emcy_code {
inline constexpr std::uint16_t kNoError = 0x0000;
inline constexpr std::uint16_t kOverCurrent = 0x2310;
inline constexpr std::uint16_t kOverVoltage = 0x3210;
inline constexpr std::uint16_t kOverTemperature = 0x4310;
inline constexpr std::uint16_t kHeartbeatConsumer = 0x8130;  // lost the master's heartbeat
inline constexpr std::uint16_t kFollowingError = 0x8611;
inline constexpr std::uint16_t kPositionLimit = 0x8612;  // software position limit
}  // namespace emcy_code

// The fixed PDO layout (docs/arm.md):
//   RPDO1 (0x200 + node, 6 bytes): controlword 0x6040 u16, target position 0x607A i32
//   TPDO1 (0x180 + node, 6 bytes): statusword 0x6041 u16, position actual 0x6064 i32
inline constexpr std::uint8_t kPdoLength = 6;
struct Rpdo1 {
  std::uint16_t controlword = 0;
  std::int32_t target_position = 0;
};
struct Tpdo1 {
  std::uint16_t statusword = 0;
  std::int32_t position_actual = 0;
};
CanFrame make_rpdo1(std::uint8_t node, const Rpdo1& pdo);
Result<Rpdo1> parse_rpdo1(const CanFrame& frame);
CanFrame make_tpdo1(std::uint8_t node, const Tpdo1& pdo);
Result<Tpdo1> parse_tpdo1(const CanFrame& frame);

// Object dictionary entries the master reads or writes.
namespace od {
inline constexpr SdoAddress kDeviceType{0x1000, 0};
inline constexpr SdoAddress kErrorRegister{0x1001, 0};
inline constexpr SdoAddress kConsumerHeartbeat{0x1016, 1};  // (node << 16) | time_ms
inline constexpr SdoAddress kProducerHeartbeat{0x1017, 0};  // u16 ms
inline constexpr SdoAddress kRpdo1CobId{0x1400, 1};
inline constexpr SdoAddress kRpdo1Type{0x1400, 2};
inline constexpr SdoAddress kRpdo1MapCount{0x1600, 0};
inline constexpr SdoAddress kRpdo1Map1{0x1600, 1};
inline constexpr SdoAddress kRpdo1Map2{0x1600, 2};
inline constexpr SdoAddress kTpdo1CobId{0x1800, 1};
inline constexpr SdoAddress kTpdo1Type{0x1800, 2};
inline constexpr SdoAddress kTpdo1MapCount{0x1A00, 0};
inline constexpr SdoAddress kTpdo1Map1{0x1A00, 1};
inline constexpr SdoAddress kTpdo1Map2{0x1A00, 2};
inline constexpr SdoAddress kControlword{0x6040, 0};
inline constexpr SdoAddress kStatusword{0x6041, 0};
inline constexpr SdoAddress kQuickStopOption{0x605A, 0};
inline constexpr SdoAddress kModesOfOperation{0x6060, 0};
inline constexpr SdoAddress kModesDisplay{0x6061, 0};
inline constexpr SdoAddress kPositionActual{0x6064, 0};
inline constexpr SdoAddress kFollowingErrorWindow{0x6065, 0};
inline constexpr SdoAddress kPositionWindow{0x6067, 0};
inline constexpr SdoAddress kTargetPosition{0x607A, 0};
inline constexpr SdoAddress kSoftwareLimitMin{0x607D, 1};
inline constexpr SdoAddress kSoftwareLimitMax{0x607D, 2};
inline constexpr SdoAddress kProfileVelocity{0x6081, 0};
inline constexpr SdoAddress kProfileAcceleration{0x6083, 0};
inline constexpr SdoAddress kProfileDeceleration{0x6084, 0};
inline constexpr SdoAddress kQuickStopDeceleration{0x6085, 0};
inline constexpr SdoAddress kSupportedModes{0x6502, 0};

// PDO mapping entries: index << 16 | subindex << 8 | bit length.
inline constexpr std::uint32_t kMapControlword = 0x60400010;
inline constexpr std::uint32_t kMapTargetPosition = 0x607A0020;
inline constexpr std::uint32_t kMapStatusword = 0x60410010;
inline constexpr std::uint32_t kMapPositionActual = 0x60640020;
inline constexpr std::uint32_t kPdoDisabled = 0x80000000;  // COB-ID bit 31

// Device type of a CiA 402 servo drive: profile 402, additional info 0x0002.
inline constexpr std::uint32_t kDeviceTypeServo = 0x00020192;
inline constexpr std::uint32_t kSupportsProfilePosition = 0x00000001;  // 0x6502 bit 0
}  // namespace od

}  // namespace petra::canopen
