#include "fsw/product_streamer.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "hal/clock.hpp"

namespace petra::fsw {
namespace {

struct Fixture {
  Fixture(std::size_t slots) : storage(tlm::TlmQueue::bytes_for(slots)), lengths(slots) {
    queue.init(storage, lengths);
    events.init(&queue, &clock);
    const auto sizes = ProductStreamer::bytes_needed(64, 48, 100);
    for (std::size_t k = 0; k < kProductKinds; ++k) {
      mem[k].resize(sizes[k]);
      spans[k] = mem[k];
    }
    streamer.init(spans, &events);
  }
  // The PRODUCT chunks in the queue (events are kept in `raised`).
  std::vector<tlm::Product> drain() {
    std::vector<tlm::Product> out;
    while (!queue.empty()) {
      auto p = tlm::decode_tm(queue.front());
      EXPECT_TRUE(p.ok());
      if (const auto* e = std::get_if<tlm::Event>(&p->body))
        raised.push_back(*e);
      else
        out.push_back(std::get<tlm::Product>(p->body));
      queue.pop();
    }
    return out;
  }
  std::vector<tlm::Event> raised_with(EventId id) const {
    std::vector<tlm::Event> out;
    for (const auto& e : raised)
      if (e.event_id == static_cast<std::uint16_t>(id)) out.push_back(e);
    return out;
  }
  std::vector<std::uint8_t> storage;
  std::vector<std::uint16_t> lengths;
  tlm::TlmQueue queue;
  hal::SystemClock clock;
  EventLog events;
  std::vector<tlm::Event> raised;
  std::array<std::vector<std::uint8_t>, kProductKinds> mem;
  std::array<std::span<std::uint8_t>, kProductKinds> spans;
  ProductStreamer streamer;
};

TEST(ProductStreamer, SubsampledImageArrivesWholeInChunks) {
  Fixture f(64);
  std::vector<std::uint8_t> img(64 * 48);
  for (std::size_t i = 0; i < img.size(); ++i) img[i] = static_cast<std::uint8_t>(i % 251);
  ASSERT_TRUE(
      f.streamer.stage_image(ProductKind::DISPARITY, 7, ConstGray8View(img.data(), 64, 48), 1, 2));
  f.streamer.pump(f.queue, {}, 100, 0);
  EXPECT_TRUE(f.streamer.idle());
  const auto chunks = f.drain();
  ASSERT_EQ(chunks.size(), 1u);  // 32 x 24 = 768 bytes: one chunk
  const auto sent = f.raised_with(EventId::PRODUCT_SENT);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].args, (std::array<std::int32_t, 4>{2, 7, 1, 768}));  // DISPARITY, id 7
  EXPECT_EQ(chunks[0].width, 32);
  EXPECT_EQ(chunks[0].height, 24);
  EXPECT_EQ(chunks[0].data_len, 768);
  EXPECT_EQ(chunks[0].data[33], img[64 * 2 + 2]);  // (x 1, y 1) of the thumbnail
}

TEST(ProductStreamer, NeverTakesTheReservedQueueSlots) {
  Fixture f(8);
  std::vector<std::uint8_t> img(64 * 48, 9);
  ASSERT_TRUE(
      f.streamer.stage_image(ProductKind::LEFT_IMAGE, 1, ConstGray8View(img.data(), 64, 48), 1, 1));
  f.streamer.pump(f.queue, {}, 100, 6);
  EXPECT_EQ(f.queue.size(), 2u);  // 8 slots, 6 kept free
  EXPECT_EQ(f.queue.dropped(), 0u);
  EXPECT_FALSE(f.streamer.idle());
  auto first = f.drain();
  f.streamer.pump(f.queue, {}, 100, 6);
  auto second = f.drain();
  EXPECT_EQ(first.size() + second.size(), 3u);  // 3072 bytes = 3 chunks
  EXPECT_EQ(second.back().chunk + 1, second.back().chunks);
}

TEST(ProductStreamer, ANewProductOfAKindStillStreamingIsRefusedWithAnEvent) {
  Fixture f(8);
  std::vector<std::uint8_t> a(64 * 48, 1), b(64 * 48, 2);
  ASSERT_TRUE(
      f.streamer.stage_image(ProductKind::LEFT_IMAGE, 1, ConstGray8View(a.data(), 64, 48), 1, 1));
  f.streamer.pump(f.queue, {}, 1, 0);  // chunk 0 of 3 on its way
  // Pair 2's image while pair 1's streams: refused, pair 1's is not cut short.
  EXPECT_FALSE(
      f.streamer.stage_image(ProductKind::LEFT_IMAGE, 2, ConstGray8View(b.data(), 64, 48), 1, 1));
  EXPECT_EQ(f.streamer.products_refused(), 1u);
  // Another kind is free.
  ASSERT_TRUE(
      f.streamer.stage_image(ProductKind::DISPARITY, 2, ConstGray8View(b.data(), 64, 48), 1, 4));
  std::vector<tlm::Product> chunks;
  for (int cycle = 0; cycle < 10 && !f.streamer.idle(); ++cycle) {
    f.streamer.pump(f.queue, {}, 100, 2);
    for (const auto& c : f.drain()) chunks.push_back(c);
  }
  EXPECT_TRUE(f.streamer.idle());
  int left_chunks = 0;
  for (const auto& c : chunks)
    if (c.product == static_cast<std::uint8_t>(ProductKind::LEFT_IMAGE)) {
      EXPECT_EQ(c.id, 1u);
      EXPECT_EQ(c.data[0], 1);
      ++left_chunks;
    }
  EXPECT_EQ(left_chunks, 3);  // all of pair 1's image
  const auto refused = f.raised_with(EventId::PRODUCT_REFUSED);
  ASSERT_EQ(refused.size(), 1u);
  EXPECT_EQ(refused[0].args, (std::array<std::int32_t, 4>{1, 2, 1, 1}));  // LEFT 2: LEFT 1 busy
  const auto sent = f.raised_with(EventId::PRODUCT_SENT);
  ASSERT_EQ(sent.size(), 2u);
  EXPECT_EQ(f.streamer.products_sent(), 2u);
  // Once pair 1's image is sent, pair 2's is taken.
  EXPECT_TRUE(
      f.streamer.stage_image(ProductKind::LEFT_IMAGE, 2, ConstGray8View(b.data(), 64, 48), 1, 1));
}

TEST(ProductStreamer, AProductTooLargeForItsBufferIsRefusedWithAnEvent) {
  Fixture f(8);
  std::vector<std::uint8_t> big(128 * 48, 3);
  EXPECT_FALSE(
      f.streamer.stage_image(ProductKind::DISPARITY, 5, ConstGray8View(big.data(), 128, 48), 1, 1));
  f.drain();
  const auto refused = f.raised_with(EventId::PRODUCT_REFUSED);
  ASSERT_EQ(refused.size(), 1u);
  EXPECT_EQ(refused[0].args, (std::array<std::int32_t, 4>{2, 5, 2, 0}));
  EXPECT_TRUE(f.streamer.idle());
}

// The proposals picture: gray staged as RGB at half size or less, writable
// for the drawing until pumped; a full-size one does not fit its buffer.
TEST(ProductStreamer, TheProposalsPictureIsGrayAsRgbAtHalfSizeOrLess) {
  Fixture f(64);
  std::vector<std::uint8_t> img(64 * 48);
  for (std::size_t i = 0; i < img.size(); ++i) img[i] = static_cast<std::uint8_t>(i % 251);
  const ConstGray8View gray(img.data(), 64, 48);
  EXPECT_TRUE(f.streamer.stage_gray_as_rgb(ProductKind::PROPOSALS, 9, gray, 1).empty());
  f.drain();
  ASSERT_EQ(f.raised_with(EventId::PRODUCT_REFUSED).size(), 1u);  // too large at full size
  const ImageView<std::uint8_t> rgb =
      f.streamer.stage_gray_as_rgb(ProductKind::PROPOSALS, 9, gray, 2);
  ASSERT_EQ(rgb.width(), 3 * 32);
  ASSERT_EQ(rgb.height(), 24);
  rgb(0, 0) = 255;  // the caller draws on it before the pump
  f.streamer.pump(f.queue, {}, 100, 0);
  const auto chunks = f.drain();
  ASSERT_EQ(chunks.size(), 3u);  // 32 x 24 x 3 = 2304 bytes
  EXPECT_EQ(chunks[0].product, 5);
  EXPECT_EQ(chunks[0].format, static_cast<std::uint8_t>(ProductFormat::RGB8));
  EXPECT_EQ(chunks[0].data[0], 255);
  EXPECT_EQ(chunks[0].data[1], img[0]);
  EXPECT_EQ(chunks[0].data[3 * 5 + 2], img[2 * 5]);  // pixel (5, 0) is image (10, 0)
}

TEST(ProductStreamer, PointCloudIsSubsampledToItsLimitAsBigEndianFloats) {
  Fixture f(64);
  std::vector<float> xyz;
  for (int i = 0; i < 300; ++i) xyz.insert(xyz.end(), {float(i), 1.5f, -2.0f});
  ASSERT_TRUE(f.streamer.stage_cloud(3, xyz, 100));
  f.streamer.pump(f.queue, {}, 100, 0);
  const auto chunks = f.drain();
  ASSERT_EQ(chunks.size(), 2u);  // 100 points x 12 bytes
  EXPECT_EQ(chunks[0].width, 100);
  EXPECT_EQ(chunks[0].total_bytes, 1200u);
  // second point is source point 3: x = 3.0f = 0x40400000
  EXPECT_EQ(chunks[0].data[12], 0x40);
  EXPECT_EQ(chunks[0].data[13], 0x40);
}

}  // namespace
}  // namespace petra::fsw
