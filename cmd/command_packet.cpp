#include "cmd/command_packet.hpp"

#include "algo/wire/ccsds.hpp"
#include "algo/wire/crc16.hpp"

namespace petra::cmd {

Result<std::size_t> encode_command_packet(const Command& c, std::uint16_t seq_count,
                                          const AuthKey& key, std::span<std::uint8_t> out) {
  const CommandDesc* desc = find_command(static_cast<std::uint8_t>(c.code));
  if (desc == nullptr) return Error::make(Errc::invalid_argument, "command: unknown function code");
  const std::size_t total = kTcOverheadBytes + desc->arg_bytes;
  if (out.size() < total)
    return Error::make(Errc::capacity_exceeded, "command: %zu bytes needed, %zu given", total,
                       out.size());
  const std::size_t arg_end = kTcHeaderBytes + desc->arg_bytes;
  if (encode_args(c.args, out.subspan(kTcHeaderBytes, desc->arg_bytes)) != desc->arg_bytes)
    return Error::make(Errc::invalid_argument, "command %s: arguments of another command",
                       desc->name);

  wire::PrimaryHeader h;
  h.type = wire::PacketType::telecommand;
  h.secondary_header = true;
  h.apid = kCommandApid;
  h.seq_flags = wire::SeqFlags::unsegmented;
  h.seq_count = seq_count;
  h.data_length = static_cast<std::uint16_t>(total - wire::kPrimaryHeaderBytes - 1);
  wire::write_primary_header(h, out);
  wire::ByteWriter w(out.subspan(wire::kPrimaryHeaderBytes, 6));
  w.u8(desc->code);
  w.u8(0);
  w.u32(c.counter);

  const Mac mac = compute_mac(key, out.first(arg_end));
  for (std::size_t i = 0; i < kMacBytes; ++i) out[arg_end + i] = mac[i];
  const std::uint16_t crc = wire::crc16_ccitt(out.first(total - kCrcBytes));
  out[total - 2] = static_cast<std::uint8_t>(crc >> 8);
  out[total - 1] = static_cast<std::uint8_t>(crc);
  return total;
}

}  // namespace petra::cmd
