// Products come down as chunks: the ground puts them back together in any
// order, and names what is still missing when a wait ends.
#include "sim/ground/product_assembler.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace petra::ground {
namespace {

// Chunk `k` of a gray `w` x 1 image whose byte i is i % 251.
tlm::Product chunk_of(std::uint8_t kind, std::uint32_t id, std::uint16_t w, std::uint16_t k) {
  tlm::Product c{};
  c.product = kind;
  c.format = 1;
  c.id = id;
  c.chunks =
      static_cast<std::uint16_t>((w + PETRA_PRODUCT_DATA_BYTES - 1) / PETRA_PRODUCT_DATA_BYTES);
  c.chunk = k;
  c.total_bytes = w;
  c.width = w;
  c.height = 1;
  const std::size_t at = static_cast<std::size_t>(k) * PETRA_PRODUCT_DATA_BYTES;
  c.data_len = static_cast<std::uint16_t>(std::min<std::size_t>(PETRA_PRODUCT_DATA_BYTES, w - at));
  for (std::size_t i = 0; i < c.data_len; ++i)
    c.data[i] = static_cast<std::uint8_t>((at + i) % 251);
  return c;
}

TEST(ProductAssembler, ChunksInAnyOrderMakeTheProductAndMissingOnesAreNamed) {
  ProductAssembler a;
  const std::uint16_t w = 2500;  // 3 chunks
  EXPECT_FALSE(a.add(chunk_of(2, 7, w, 2)));
  EXPECT_FALSE(a.add(chunk_of(4, 7, w, 0)));  // another product, never finished
  EXPECT_FALSE(a.add(chunk_of(2, 7, w, 0)));
  EXPECT_FALSE(a.add(chunk_of(2, 7, w, 0)));  // a repeat changes nothing
  EXPECT_EQ(a.incomplete(), 2u);
  EXPECT_EQ(a.incomplete_text(), "disparity 7 (2 of 3 chunks), point_cloud 7 (1 of 3 chunks)");
  const auto done = a.add(chunk_of(2, 7, w, 1));
  ASSERT_TRUE(done);
  EXPECT_EQ(done->kind, 2);
  ASSERT_EQ(done->bytes.size(), w);
  for (std::size_t i = 0; i < w; ++i) ASSERT_EQ(done->bytes[i], i % 251) << "byte " << i;
  EXPECT_EQ(a.incomplete_text(), "point_cloud 7 (1 of 3 chunks)");
}

}  // namespace
}  // namespace petra::ground
