// Frame checks and gray conversion, on synthetic frames: every way a driver can
// hand over a broken frame ends as an error value naming the fault.
#include "hal/video_frame.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "hal/stereo_pairing.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra::hal {
namespace {

FrameFormat grey(int w, int h) {
  return FrameFormat{PixelFormat::grey, w, h, static_cast<std::uint32_t>(w),
                     static_cast<std::uint32_t>(w * h)};
}

RawFrame raw_frame(const std::vector<std::uint8_t>& px, std::uint32_t seq, std::int64_t t_ns) {
  RawFrame f;
  f.data = px.data();
  f.bytes_used = static_cast<std::uint32_t>(px.size());
  f.sequence = seq;
  f.time_ns = t_ns;
  return f;
}

TEST(PixelFormat, NamesAndFourccRoundTrip) {
  for (PixelFormat f : {PixelFormat::grey, PixelFormat::y16, PixelFormat::yuyv, PixelFormat::rgb24,
                        PixelFormat::bgr24}) {
    EXPECT_EQ(*pixel_format_from_name(pixel_format_name(f)), f);
    EXPECT_EQ(*pixel_format_from_fourcc(pixel_format_fourcc(f)), f);
  }
  EXPECT_EQ(pixel_format_fourcc(PixelFormat::grey), 0x59455247u);  // 'G','R','E','Y'
  auto bad = pixel_format_from_name("MJPG");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(std::strstr(bad.error().message, "MJPG"), nullptr);
  EXPECT_FALSE(pixel_format_from_fourcc(0x47504a4d).ok());
}

TEST(CheckNegotiated, RefusesWhatTheDriverChanged) {
  FrameFormat f = grey(640, 480);
  EXPECT_TRUE(check_negotiated(f, PixelFormat::grey, 640, 480).ok());
  auto size = check_negotiated(f, PixelFormat::grey, 1000, 700);
  ASSERT_FALSE(size.ok());
  EXPECT_STREQ(size.error().message, "format: device gives 640x480, configured 1000x700");
  EXPECT_EQ(check_negotiated(f, PixelFormat::y16, 640, 480).code(), Errc::wrong_type);
  FrameFormat short_line = f;
  short_line.pixel = PixelFormat::yuyv;  // needs 1280 bytes a line
  EXPECT_EQ(check_negotiated(short_line, PixelFormat::yuyv, 640, 480).code(),
            Errc::invalid_argument);
  FrameFormat short_image = f;
  short_image.image_bytes = 640 * 479;
  EXPECT_EQ(check_negotiated(short_image, PixelFormat::grey, 640, 480).code(),
            Errc::invalid_argument);
}

TEST(FrameChecker, AcceptsAnOrderlyStream) {
  std::vector<std::uint8_t> px(16 * 8, 7);
  FrameChecker c;
  c.reset(grey(16, 8));
  FrameFault fault = FrameFault::driver_error;
  test::HeapScope heap;
  for (std::uint32_t s = 5; s < 50; ++s) {
    ASSERT_TRUE(c.check(raw_frame(px, s, 1000 + s * 33'000'000LL), fault).ok()) << s;
    EXPECT_EQ(fault, FrameFault::none);
  }
  EXPECT_EQ(heap.allocations(), 0u);
}

TEST(FrameChecker, EachBrokenFrameIsAnErrorNamingTheFault) {
  std::vector<std::uint8_t> px(16 * 8, 7);
  std::vector<std::uint8_t> short_px(16 * 8 - 1, 7);
  std::vector<std::uint8_t> long_px(16 * 8 + 1, 7);
  struct Case {
    const char* name;
    RawFrame second;
    FrameFault fault;
    const char* words;
  };
  RawFrame flagged = raw_frame(px, 2, 2000);
  flagged.driver_error = true;
  const Case cases[] = {
      {"driver flag", flagged, FrameFault::driver_error, "corrupted"},
      {"short", raw_frame(short_px, 2, 2000), FrameFault::wrong_size, "127 bytes"},
      {"long", raw_frame(long_px, 2, 2000), FrameFault::wrong_size, "129 bytes"},
      {"gap", raw_frame(px, 5, 2000), FrameFault::sequence_gap, "3 frame(s) lost after 1"},
      {"same seq", raw_frame(px, 1, 2000), FrameFault::sequence_backwards, "went back"},
      {"seq back", raw_frame(px, 0, 2000), FrameFault::sequence_backwards, "went back"},
      {"time back", raw_frame(px, 2, 999), FrameFault::timestamp_backwards, "not after"},
      {"time same", raw_frame(px, 2, 1000), FrameFault::timestamp_backwards, "not after"},
  };
  for (const Case& k : cases) {
    FrameChecker c;
    c.reset(grey(16, 8));
    FrameFault fault = FrameFault::none;
    ASSERT_TRUE(c.check(raw_frame(px, 1, 1000), fault).ok());
    auto s = c.check(k.second, fault);
    ASSERT_FALSE(s.ok()) << k.name;
    EXPECT_EQ(s.code(), Errc::parse_error) << k.name;
    EXPECT_EQ(fault, k.fault) << k.name << ": " << frame_fault_name(fault);
    EXPECT_NE(std::strstr(s.error().message, k.words), nullptr) << s.error().message;
  }
}

TEST(FrameChecker, OneFaultIsOneErrorNotACascade) {
  std::vector<std::uint8_t> px(16 * 8, 7);
  FrameChecker c;
  c.reset(grey(16, 8));
  FrameFault fault;
  ASSERT_TRUE(c.check(raw_frame(px, 1, 1000), fault).ok());
  EXPECT_FALSE(c.check(raw_frame(px, 9, 2000), fault).ok());  // 7 lost
  EXPECT_TRUE(c.check(raw_frame(px, 10, 3000), fault).ok());  // continues from 9
  c.reset(grey(16, 8));                                       // a new run: no previous frame
  EXPECT_TRUE(c.check(raw_frame(px, 100, 100), fault).ok());
}

TEST(FrameChecker, GapsOfAFreeRunningCameraAreOnlyCounted) {
  std::vector<std::uint8_t> px(16 * 8, 7);
  FrameChecker c;
  c.reset(grey(16, 8), /*gaps_are_faults=*/false);
  FrameFault fault;
  ASSERT_TRUE(c.check(raw_frame(px, 1, 1000), fault).ok());
  EXPECT_TRUE(c.check(raw_frame(px, 5, 2000), fault).ok());
  EXPECT_EQ(c.lost(), 3u);
  EXPECT_TRUE(c.check(raw_frame(px, 6, 3000), fault).ok());
  EXPECT_EQ(c.lost(), 0u);
  EXPECT_FALSE(c.check(raw_frame(px, 6, 4000), fault).ok());  // a repeat is still a fault
  EXPECT_EQ(fault, FrameFault::sequence_backwards);
}

TEST(FrameChecker, SequenceCounterWrapsLikeTheDriver) {
  std::vector<std::uint8_t> px(16 * 8, 7);
  FrameChecker c;
  c.reset(grey(16, 8));
  FrameFault fault;
  ASSERT_TRUE(c.check(raw_frame(px, UINT32_MAX - 1, 1000), fault).ok());
  EXPECT_TRUE(c.check(raw_frame(px, UINT32_MAX, 2000), fault).ok());
  EXPECT_TRUE(c.check(raw_frame(px, 0, 3000), fault).ok());
  auto gap = c.check(raw_frame(px, 3, 4000), fault);
  EXPECT_EQ(fault, FrameFault::sequence_gap) << (gap.ok() ? "" : gap.error().message);
}

TEST(ConvertToGray, TakesLumaFromEachFormat) {
  // 4x2 image with 2 bytes of padding per line.
  const std::uint8_t luma[2][4] = {{10, 20, 30, 40}, {50, 60, 70, 80}};
  std::array<std::uint8_t, 8> out{};
  auto view = Gray8View(out.data(), 4, 2);

  std::vector<std::uint8_t> g = {10, 20, 30, 40, 0, 0, 50, 60, 70, 80, 0, 0};
  FrameFormat fg{PixelFormat::grey, 4, 2, 6, 12};
  ASSERT_TRUE(convert_to_gray(raw_frame(g, 0, 0), fg, 0, view).ok());
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) EXPECT_EQ(view(x, y), luma[y][x]);

  std::vector<std::uint8_t> y16;  // little-endian, value in the high byte
  std::vector<std::uint8_t> yuyv;
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 4; ++x) {
      y16.push_back(0x5A);
      y16.push_back(luma[y][x]);
      yuyv.push_back(luma[y][x]);
      yuyv.push_back(x % 2 == 0 ? 128 : 200);  // U or V
    }
  }
  FrameFormat f16{PixelFormat::y16, 4, 2, 8, 16};
  out.fill(0);
  ASSERT_TRUE(convert_to_gray(raw_frame(y16, 0, 0), f16, 0, view).ok());
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) EXPECT_EQ(view(x, y), luma[y][x]);
  FrameFormat fyuyv{PixelFormat::yuyv, 4, 2, 8, 16};
  out.fill(0);
  ASSERT_TRUE(convert_to_gray(raw_frame(yuyv, 0, 0), fyuyv, 0, view).ok());
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) EXPECT_EQ(view(x, y), luma[y][x]);
}

TEST(ConvertToGray, ColourIsRec601LumaInEitherByteOrder) {
  // white, black, pure red, green, blue, and a mid grey
  std::vector<std::uint8_t> rgb = {255, 255, 255, 0, 0, 0,   255, 0,   0,
                                   0,   255, 0,   0, 0, 255, 128, 128, 128};
  std::vector<std::uint8_t> bgr;
  for (std::size_t i = 0; i < rgb.size(); i += 3)
    bgr.insert(bgr.end(), {rgb[i + 2], rgb[i + 1], rgb[i]});
  const std::array<std::uint8_t, 6> want{255, 0, 77, 149, 29, 128};
  std::array<std::uint8_t, 6> out{};
  FrameFormat f{PixelFormat::rgb24, 6, 1, 18, 18};
  ASSERT_TRUE(convert_to_gray(raw_frame(rgb, 0, 0), f, 0, Gray8View(out.data(), 6, 1)).ok());
  EXPECT_EQ(out, want);
  f.pixel = PixelFormat::bgr24;
  out.fill(0);
  ASSERT_TRUE(convert_to_gray(raw_frame(bgr, 0, 0), f, 0, Gray8View(out.data(), 6, 1)).ok());
  EXPECT_EQ(out, want);
}

TEST(ConvertToGray, StretchesVideoRangeLumaToFullRange) {
  std::vector<std::uint8_t> yuyv = {16, 128, 235, 128, 179, 128, 5, 128, 250, 128, 126, 128};
  FrameFormat f{PixelFormat::yuyv, 6, 1, 12, 12, true};
  std::array<std::uint8_t, 6> out{};
  ASSERT_TRUE(convert_to_gray(raw_frame(yuyv, 0, 0), f, 0, Gray8View(out.data(), 6, 1)).ok());
  EXPECT_EQ(out, (std::array<std::uint8_t, 6>{0, 255, 190, 0, 255, 128}));
  f.limited_range = false;
  ASSERT_TRUE(convert_to_gray(raw_frame(yuyv, 0, 0), f, 0, Gray8View(out.data(), 6, 1)).ok());
  EXPECT_EQ(out, (std::array<std::uint8_t, 6>{16, 235, 179, 5, 250, 126}));
}

TEST(ConvertToGray, SplitsASideBySidePairAndRefusesRegionsOutside) {
  std::vector<std::uint8_t> sbs = {1, 2, 3, 4, 5, 6, 7, 8};  // 4x2: left 2 columns, right 2
  FrameFormat f{PixelFormat::grey, 4, 2, 4, 8};
  std::array<std::uint8_t, 4> l{}, r{};
  ASSERT_TRUE(convert_to_gray(raw_frame(sbs, 0, 0), f, 0, Gray8View(l.data(), 2, 2)).ok());
  ASSERT_TRUE(convert_to_gray(raw_frame(sbs, 0, 0), f, 2, Gray8View(r.data(), 2, 2)).ok());
  EXPECT_EQ(l, (std::array<std::uint8_t, 4>{1, 2, 5, 6}));
  EXPECT_EQ(r, (std::array<std::uint8_t, 4>{3, 4, 7, 8}));
  EXPECT_EQ(convert_to_gray(raw_frame(sbs, 0, 0), f, 3, Gray8View(r.data(), 2, 2)).code(),
            Errc::out_of_range);
  std::vector<std::uint8_t> cut(sbs.begin(), sbs.begin() + 5);
  EXPECT_EQ(convert_to_gray(raw_frame(cut, 0, 0), f, 0, Gray8View(l.data(), 2, 2)).code(),
            Errc::invalid_argument);
}

TEST(DeinterleavePair, ByteZeroIsLeftByteOneIsRight) {
  std::vector<std::uint8_t> px = {1, 101, 2, 102, 3, 103, 4, 104};  // 2x2, 2 bytes/pixel
  FrameFormat f{PixelFormat::y16, 2, 2, 4, 8};
  std::array<std::uint8_t, 4> l{}, r{};
  test::HeapScope heap;
  ASSERT_TRUE(deinterleave_pair(raw_frame(px, 0, 0), f, Gray8View(l.data(), 2, 2),
                                Gray8View(r.data(), 2, 2))
                  .ok());
  EXPECT_EQ(heap.allocations(), 0u);
  EXPECT_EQ(l, (std::array<std::uint8_t, 4>{1, 2, 3, 4}));
  EXPECT_EQ(r, (std::array<std::uint8_t, 4>{101, 102, 103, 104}));
  FrameFormat g{PixelFormat::grey, 2, 2, 2, 4};
  EXPECT_EQ(deinterleave_pair(raw_frame(px, 0, 0), g, Gray8View(l.data(), 2, 2),
                              Gray8View(r.data(), 2, 2))
                .code(),
            Errc::wrong_type);
}

TEST(StereoPairing, PairsWithinSkewElseReadsTheOlderSideAgain) {
  // pair_step is constexpr: checked at compile time too.
  static_assert(pair_step(1000, 1500, 500) == PairStep::pair);
  EXPECT_EQ(pair_step(1000, 1501, 500), PairStep::next_left);
  EXPECT_EQ(pair_step(2000, 1000, 500), PairStep::next_right);
  EXPECT_EQ(pair_step(5, 5, 0), PairStep::pair);
}

}  // namespace
}  // namespace petra::hal
