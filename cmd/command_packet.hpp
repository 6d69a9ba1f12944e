// Building a signed telecommand packet (ground side, tests, fuzzing). The
// flight side only reads packets, through cmd/validator.
#pragma once

#include <cstdint>
#include <span>

#include "algo/core/result.hpp"
#include "cmd/auth.hpp"
#include "cmd/commands.hpp"

namespace petra::cmd {

// Writes the packet for `c` (header, arguments, HMAC, CRC) into out and
// returns its size. seq_count is the CCSDS sequence count (ground's choice).
Result<std::size_t> encode_command_packet(const Command& c, std::uint16_t seq_count,
                                          const AuthKey& key, std::span<std::uint8_t> out);

}  // namespace petra::cmd
