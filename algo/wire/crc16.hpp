// CRC-16-CCITT as CCSDS uses it for telecommand frames: polynomial 0x1021,
// initial value 0xFFFF, no reflection, no final XOR ("CRC-16/CCITT-FALSE";
// check value of "123456789" is 0x29B1).
#pragma once

#include <cstdint>
#include <span>

namespace petra::wire {

std::uint16_t crc16_ccitt(std::span<const std::uint8_t> bytes);

}  // namespace petra::wire
