#include "tlm/telemetry.hpp"

#include "algo/wire/crc16.hpp"

namespace petra::tlm {

const TmDesc* find_telemetry(std::uint16_t apid) {
  for (const TmDesc& t : kTelemetryTable)
    if (t.apid == apid) return &t;
  return nullptr;
}

std::size_t encode_tm(std::uint16_t apid, std::uint16_t seq_count, wire::SeqFlags flags,
                      TmTime time, std::span<const std::uint8_t> fields,
                      std::span<std::uint8_t> out) {
  const std::size_t total = kTmHeaderBytes + fields.size() + kTmCrcBytes;
  if (out.size() < total || total - wire::kPrimaryHeaderBytes - 1 > 0xFFFF) return 0;
  wire::PrimaryHeader h;
  h.type = wire::PacketType::telemetry;
  h.secondary_header = true;
  h.apid = apid;
  h.seq_flags = flags;
  h.seq_count = seq_count;
  h.data_length = static_cast<std::uint16_t>(total - wire::kPrimaryHeaderBytes - 1);
  wire::write_primary_header(h, out);
  wire::ByteWriter w(out.subspan(wire::kPrimaryHeaderBytes, 8));
  w.u32(time.seconds);
  w.u32(time.micros);
  // fields may already sit in place (typed encode_tm writes them there first).
  if (fields.data() != out.data() + kTmHeaderBytes)
    for (std::size_t i = 0; i < fields.size(); ++i) out[kTmHeaderBytes + i] = fields[i];
  const std::uint16_t crc = wire::crc16_ccitt(out.first(total - kTmCrcBytes));
  out[total - 2] = static_cast<std::uint8_t>(crc >> 8);
  out[total - 1] = static_cast<std::uint8_t>(crc);
  return total;
}

Result<TmPacket> decode_tm(std::span<const std::uint8_t> datagram) {
  const std::size_t size = datagram.size();
  if (size < kTmHeaderBytes + kTmCrcBytes)
    return Error::make(Errc::parse_error, "telemetry: %zu bytes is shorter than a header", size);
  TmPacket p;
  p.header.primary = wire::read_primary_header(datagram);
  const wire::PrimaryHeader& h = p.header.primary;
  if (h.version != 0 || h.type != wire::PacketType::telemetry || !h.secondary_header)
    return Error::make(Errc::parse_error, "telemetry: primary header is not a TM packet");
  if (wire::packet_bytes(h) != size)
    return Error::make(Errc::parse_error,
                       "telemetry: length field says %zu bytes, datagram has %zu",
                       wire::packet_bytes(h), size);
  const std::uint16_t crc =
      static_cast<std::uint16_t>((datagram[size - 2] << 8) | datagram[size - 1]);
  if (wire::crc16_ccitt(datagram.first(size - kTmCrcBytes)) != crc)
    return Error::make(Errc::parse_error, "telemetry: CRC mismatch (APID 0x%03x)", h.apid);
  const TmDesc* desc = find_telemetry(h.apid);
  if (desc == nullptr)
    return Error::make(Errc::parse_error, "telemetry: unknown APID 0x%03x", h.apid);
  if (size != kTmHeaderBytes + desc->payload_bytes + kTmCrcBytes)
    return Error::make(Errc::parse_error, "telemetry %s: %zu bytes, expected %zu", desc->name, size,
                       kTmHeaderBytes + desc->payload_bytes + kTmCrcBytes);
  wire::ByteReader time(datagram.subspan(wire::kPrimaryHeaderBytes, 8));
  p.header.time.seconds = time.u32();
  p.header.time.micros = time.u32();
  wire::ByteReader r(datagram.subspan(kTmHeaderBytes, desc->payload_bytes));
  switch (static_cast<Apid>(h.apid)) {
#define PETRA_TM_DECODE(Name, NAME, apid, d, FIELDS) \
  case Apid::NAME: {                                 \
    Name body;                                       \
    body.read(r);                                    \
    p.body = body;                                   \
    break;                                           \
  }
    PETRA_TELEMETRY(PETRA_TM_DECODE)
#undef PETRA_TM_DECODE
  }
  return p;
}

}  // namespace petra::tlm
