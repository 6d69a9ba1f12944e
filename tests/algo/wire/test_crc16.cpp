#include "algo/wire/crc16.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>

namespace petra::wire {
namespace {

TEST(Crc16, CcittFalseCheckValue) {
  const std::array<std::uint8_t, 9> digits{'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(crc16_ccitt(digits), 0x29B1);
}

TEST(Crc16, EmptyInputIsTheInitialValue) {
  EXPECT_EQ(crc16_ccitt({}), 0xFFFF);
}

TEST(Crc16, EverySingleBitFlipIsDetected) {
  std::array<std::uint8_t, 64> data{};
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint8_t>(i * 37 + 5);
  const std::uint16_t good = crc16_ccitt(data);
  for (std::size_t i = 0; i < data.size(); ++i)
    for (int b = 0; b < 8; ++b) {
      data[i] ^= static_cast<std::uint8_t>(1u << b);
      EXPECT_NE(crc16_ccitt(data), good) << "byte " << i << " bit " << b;
      data[i] ^= static_cast<std::uint8_t>(1u << b);
    }
}

}  // namespace
}  // namespace petra::wire
