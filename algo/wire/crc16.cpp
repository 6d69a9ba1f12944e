#include "algo/wire/crc16.hpp"

#include <array>

namespace petra::wire {

namespace {

// Table computed at compile time: one lookup per byte instead of eight shifts.
constexpr std::array<std::uint16_t, 256> make_table() {
  std::array<std::uint16_t, 256> t{};
  for (unsigned i = 0; i < 256; ++i) {
    unsigned c = i << 8;
    for (int b = 0; b < 8; ++b) c = (c & 0x8000u) ? ((c << 1) ^ 0x1021u) : (c << 1);
    t[i] = static_cast<std::uint16_t>(c & 0xFFFFu);
  }
  return t;
}

constexpr auto kTable = make_table();

}  // namespace

std::uint16_t crc16_ccitt(std::span<const std::uint8_t> bytes) {
  unsigned crc = 0xFFFFu;
  for (std::uint8_t b : bytes) crc = ((crc << 8) ^ kTable[((crc >> 8) ^ b) & 0xFFu]) & 0xFFFFu;
  return static_cast<std::uint16_t>(crc);
}

}  // namespace petra::wire
