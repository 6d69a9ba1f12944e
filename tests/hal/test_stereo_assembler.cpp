// Stereo pair assembly over scripted frame sources: pairing by timestamp,
// the skew bound, triggered capture, one-camera layouts and every error path,
// without devices.
#include "hal/stereo_assembler.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <vector>

#include "hal/gpio_sim.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra::hal {
namespace {

// Frames given in advance: (sequence, time in ms, pixel value) or an error.
class ScriptedSource final : public FrameSource {
 public:
  struct Step {
    std::uint32_t sequence;
    std::int64_t time_ms;
    std::uint8_t value;
    Errc error = Errc::ok;
  };
  ScriptedSource(int width, int height, PixelFormat pixel, std::vector<Step> steps)
      : steps_(std::move(steps)) {
    format_.pixel = pixel;
    format_.width = width;
    format_.height = height;
    format_.bytes_per_line = static_cast<std::uint32_t>(width * bytes_per_pixel(pixel));
    format_.image_bytes = format_.bytes_per_line * static_cast<std::uint32_t>(height);
    pixels_.resize(format_.image_bytes);
  }
  Result<RawFrame> next(int) override {
    if (index_ >= steps_.size()) {
      health_.last_fault = FrameFault::timeout;
      return Error::make(Errc::timeout, "script ran out");
    }
    const Step& s = steps_[index_++];
    if (s.error != Errc::ok) {
      health_.last_fault = s.error == Errc::timeout ? FrameFault::timeout : FrameFault::device_lost;
      return Error::make(s.error, "scripted %s", errc_name(s.error));
    }
    // Byte k of the frame is value + k (so layouts can be told apart).
    for (std::size_t k = 0; k < pixels_.size(); ++k)
      pixels_[k] = static_cast<std::uint8_t>(s.value + k);
    RawFrame f;
    f.data = pixels_.data();
    f.bytes_used = format_.image_bytes;
    f.sequence = s.sequence;
    f.time_ns = s.time_ms * 1'000'000;
    return f;
  }
  Result<int> flush() override {
    ++flushes;
    return 0;
  }
  const FrameFormat& format() const override { return format_; }
  const CameraHealth& health() const override { return health_; }
  std::size_t reads() const { return index_; }
  int flushes = 0;

 private:
  std::vector<Step> steps_;
  std::size_t index_ = 0;
  std::vector<std::uint8_t> pixels_;
  FrameFormat format_{};
  CameraHealth health_{};
};

StereoTiming timing(std::int64_t max_skew_us, StereoLayout layout = StereoLayout::two_devices) {
  StereoTiming t;
  t.layout = layout;
  t.width = 4;
  t.height = 2;
  t.max_skew_us = max_skew_us;
  t.max_pair_frames = 4;
  return t;
}

struct Views {
  std::array<std::uint8_t, 8> l{}, r{};
  Gray8View left() { return Gray8View(l.data(), 4, 2); }
  Gray8View right() { return Gray8View(r.data(), 4, 2); }
};

TEST(StereoAssembler, PairsTheFirstFramesWhenWithinTheSkew) {
  ScriptedSource left(4, 2, PixelFormat::grey, {{10, 1000, 1}});
  ScriptedSource right(4, 2, PixelFormat::grey, {{20, 1002, 100}});
  Views v;
  StereoHealth h;
  test::HeapScope heap;
  auto info = assemble_pair(timing(5000), left, &right, v.left(), v.right(), h);
  EXPECT_EQ(heap.allocations(), 0u);
  ASSERT_TRUE(info.ok()) << info.error().message;
  EXPECT_EQ(info->left_sequence, 10u);
  EXPECT_EQ(info->right_sequence, 20u);
  EXPECT_EQ(info->frames_skipped, 0u);
  EXPECT_EQ(v.l[0], 1);
  EXPECT_EQ(v.r[7], 107);
  EXPECT_EQ(left.flushes, 1);  // free running: stale frames dropped first
  EXPECT_EQ(right.flushes, 1);
  EXPECT_EQ(h.pairs, 1u);
}

TEST(StereoAssembler, ReadsTheOlderSideAgainUntilThePairFits) {
  // Left runs 25 ms behind; its next frames at 1033 and 1066 ms meet right's 1070.
  ScriptedSource left(4, 2, PixelFormat::grey, {{1, 1000, 0}, {2, 1033, 0}, {3, 1066, 0}});
  ScriptedSource right(4, 2, PixelFormat::grey, {{7, 1070, 0}});
  Views v;
  StereoHealth h;
  auto info = assemble_pair(timing(5000), left, &right, v.left(), v.right(), h);
  ASSERT_TRUE(info.ok()) << info.error().message;
  EXPECT_EQ(info->left_sequence, 3u);
  EXPECT_EQ(info->frames_skipped, 2u);
  EXPECT_EQ(left.reads(), 3u);
}

TEST(StereoAssembler, GivesUpAfterTheFrameBudgetNamingTheSkew) {
  ScriptedSource left(4, 2, PixelFormat::grey,
                      {{1, 0, 0}, {2, 40, 0}, {3, 80, 0}, {4, 120, 0}, {5, 160, 0}});
  ScriptedSource right(4, 2, PixelFormat::grey, {{1, 1000, 0}});
  Views v;
  StereoHealth h;
  auto info = assemble_pair(timing(5000), left, &right, v.left(), v.right(), h);
  ASSERT_FALSE(info.ok());
  EXPECT_EQ(info.code(), Errc::timeout);
  EXPECT_STREQ(info.error().message,
               "stereo: no pair within 5000 us (skew 880000 us after 4 left and 1 right frames)");
  EXPECT_EQ(h.last_fault, FrameFault::skew);
  EXPECT_EQ(h.skew_failures, 1u);
  EXPECT_EQ(h.pairs, 0u);
}

TEST(StereoAssembler, TriggeredPairPulsesOnceAndAcceptsNoSecondChance) {
  SimGpioOutput trigger;
  ScriptedSource left(4, 2, PixelFormat::grey, {{1, 1000, 0}, {2, 1010, 0}});
  ScriptedSource right(4, 2, PixelFormat::grey, {{1, 1010, 0}});
  StereoTiming t = timing(1000);
  t.trigger = &trigger;
  t.trigger_width_us = 50;
  Views v;
  StereoHealth h;
  auto info = assemble_pair(t, left, &right, v.left(), v.right(), h);
  EXPECT_EQ(trigger.rising_edges(), 1u);
  EXPECT_EQ(left.flushes, 0);  // triggered frames are never stale
  ASSERT_FALSE(info.ok());
  EXPECT_EQ(h.last_fault, FrameFault::skew);
  EXPECT_EQ(left.reads(), 1u);
}

TEST(StereoAssembler, ACameraErrorEndsTheAcquisitionWithItsFault) {
  ScriptedSource left(4, 2, PixelFormat::grey, {{1, 1000, 0}});
  ScriptedSource right(4, 2, PixelFormat::grey, {{0, 0, 0, Errc::io_error}});
  Views v;
  StereoHealth h;
  auto info = assemble_pair(timing(5000), left, &right, v.left(), v.right(), h);
  ASSERT_FALSE(info.ok());
  EXPECT_EQ(info.code(), Errc::io_error);
  EXPECT_EQ(h.last_fault, FrameFault::device_lost);
  ScriptedSource quiet(4, 2, PixelFormat::grey, {});
  auto none = assemble_pair(timing(5000), quiet, &right, v.left(), v.right(), h);
  EXPECT_EQ(none.code(), Errc::timeout);
  EXPECT_EQ(h.last_fault, FrameFault::timeout);
}

TEST(StereoAssembler, OneCameraSideBySideAndPixelInterleaved) {
  Views v;
  StereoHealth h;
  ScriptedSource sbs(8, 2, PixelFormat::grey, {{1, 1000, 0}});
  auto a =
      assemble_pair(timing(0, StereoLayout::side_by_side), sbs, nullptr, v.left(), v.right(), h);
  ASSERT_TRUE(a.ok()) << a.error().message;
  EXPECT_EQ(v.l, (std::array<std::uint8_t, 8>{0, 1, 2, 3, 8, 9, 10, 11}));
  EXPECT_EQ(v.r, (std::array<std::uint8_t, 8>{4, 5, 6, 7, 12, 13, 14, 15}));
  EXPECT_EQ(a->left_time_ns, a->right_time_ns);
  ScriptedSource inter(4, 2, PixelFormat::y16, {{1, 1000, 0}});
  auto b = assemble_pair(timing(0, StereoLayout::pixel_interleaved), inter, nullptr, v.left(),
                         v.right(), h);
  ASSERT_TRUE(b.ok()) << b.error().message;
  EXPECT_EQ(v.l, (std::array<std::uint8_t, 8>{0, 2, 4, 6, 8, 10, 12, 14}));
  EXPECT_EQ(v.r, (std::array<std::uint8_t, 8>{1, 3, 5, 7, 9, 11, 13, 15}));
  ScriptedSource narrow(4, 2, PixelFormat::grey, {{1, 1000, 0}});
  EXPECT_EQ(
      assemble_pair(timing(0, StereoLayout::side_by_side), narrow, nullptr, v.left(), v.right(), h)
          .code(),
      Errc::invalid_argument);
}

TEST(StereoAssembler, WrongViewsAndMissingRightCameraAreRefused) {
  ScriptedSource left(4, 2, PixelFormat::grey, {{1, 1000, 0}});
  std::array<std::uint8_t, 8> small{};
  Views v;
  StereoHealth h;
  EXPECT_EQ(
      assemble_pair(timing(0), left, &left, Gray8View(small.data(), 2, 2), v.right(), h).code(),
      Errc::invalid_argument);
  EXPECT_EQ(assemble_pair(timing(0), left, nullptr, v.left(), v.right(), h).code(),
            Errc::invalid_argument);
  EXPECT_EQ(left.reads(), 0u);
}

TEST(StereoTiming, BadSettingsAreNamed) {
  StereoTiming t = timing(0);
  EXPECT_TRUE(check_stereo_timing(t).ok());
  t.max_skew_us = -1;
  EXPECT_NE(std::strstr(check_stereo_timing(t).error().message, "max_skew_us"), nullptr);
  t = timing(0);
  t.max_pair_frames = 65;
  EXPECT_EQ(check_stereo_timing(t).code(), Errc::invalid_argument);
  SimGpioOutput trig;
  t = timing(0);
  t.trigger = &trig;
  t.trigger_width_us = 0;
  EXPECT_EQ(check_stereo_timing(t).code(), Errc::invalid_argument);
}

}  // namespace
}  // namespace petra::hal
