// Telemetry packets as values, generated from tlm/tlm_defs.hpp, and their
// codec. Packet layout (big-endian), docs/icd.md "Telemetry packet":
//   [0,6)   CCSDS primary header: type 0, secondary header 1, the packet's APID
//   [6,10)  time, seconds (u32, Unix time)   [10,14) microseconds (u32)
//   [14,..) fields of the packet
//   last 2  CRC-16-CCITT over every byte before it
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <variant>

#include "algo/core/result.hpp"
#include "algo/wire/ccsds.hpp"
#include "tlm/tlm_defs.hpp"

namespace petra::tlm {

inline constexpr std::size_t kTmHeaderBytes = 14;
inline constexpr std::size_t kTmCrcBytes = 2;

enum class Apid : std::uint16_t {
#define PETRA_TM_ENUM(Name, NAME, apid, desc, FIELDS) NAME = (apid),
  PETRA_TELEMETRY(PETRA_TM_ENUM)
#undef PETRA_TM_ENUM
};

#define PETRA_TM_STRUCT(Name, NAME, apid, desc, FIELDS) PETRA_WIRE_STRUCT(Name, FIELDS)
PETRA_TELEMETRY(PETRA_TM_STRUCT)
#undef PETRA_TM_STRUCT

// APID of each packet type.
template <class T>
struct ApidOf;
#define PETRA_TM_APID(Name, NAME, apid, desc, FIELDS) \
  template <>                                         \
  struct ApidOf<Name> {                               \
    static constexpr Apid value = Apid::NAME;         \
  };
PETRA_TELEMETRY(PETRA_TM_APID)
#undef PETRA_TM_APID

struct TmDesc {
  const char* name;
  std::uint16_t apid;
  const char* description;
  std::span<const wire::FieldDesc> fields;
  std::size_t payload_bytes;
};

inline constexpr TmDesc kTelemetryTable[] = {
#define PETRA_TM_DESC(Name, NAME, apid, desc, FIELDS) \
  TmDesc{#NAME, apid, desc, Name::fields(), Name::wire_bytes()},
    PETRA_TELEMETRY(PETRA_TM_DESC)
#undef PETRA_TM_DESC
};

constexpr std::span<const TmDesc> telemetry_table() {
  return {kTelemetryTable, sizeof(kTelemetryTable) / sizeof(kTelemetryTable[0])};
}

const TmDesc* find_telemetry(std::uint16_t apid);

constexpr std::size_t max_tm_bytes() {
  std::size_t n = 0;
  for (const TmDesc& t : kTelemetryTable) n = t.payload_bytes > n ? t.payload_bytes : n;
  return kTmHeaderBytes + n + kTmCrcBytes;
}
inline constexpr std::size_t kMaxTmBytes = max_tm_bytes();

struct TmTime {
  std::uint32_t seconds = 0;
  std::uint32_t micros = 0;
};

struct TmHeader {
  wire::PrimaryHeader primary;
  TmTime time;
};

// Writes header, fields and CRC of one packet; returns its size (0 if out is too small).
std::size_t encode_tm(std::uint16_t apid, std::uint16_t seq_count, wire::SeqFlags flags,
                      TmTime time, std::span<const std::uint8_t> fields,
                      std::span<std::uint8_t> out);

template <class T>
std::size_t encode_tm(const T& packet, std::uint16_t seq_count, wire::SeqFlags flags, TmTime time,
                      std::span<std::uint8_t> out) {
  if (out.size() < kTmHeaderBytes + T::wire_bytes() + kTmCrcBytes) return 0;
  wire::ByteWriter w(out.subspan(kTmHeaderBytes, T::wire_bytes()));
  packet.write(w);
  return encode_tm(static_cast<std::uint16_t>(ApidOf<T>::value), seq_count, flags, time,
                   out.subspan(kTmHeaderBytes, T::wire_bytes()), out);
}

// One decoded telemetry packet (ground tools, tests).
using Body = std::variant<std::monostate
#define PETRA_TM_ALT(Name, NAME, apid, desc, FIELDS) , Name
                              PETRA_TELEMETRY(PETRA_TM_ALT)
#undef PETRA_TM_ALT
                          >;

struct TmPacket {
  TmHeader header;
  Body body;
};

// Verifies and decodes one datagram: size, header, length field, CRC, APID,
// payload size. Errors name the check that failed.
Result<TmPacket> decode_tm(std::span<const std::uint8_t> datagram);

}  // namespace petra::tlm
