// V4L2 capture. Configuration errors are checked everywhere; the streaming
// tests need vivid (the bench loads three capture-only instances): on a host
// without /dev/video* they skip, and the HIL guest runs them, injecting faults
// through vivid's controls (dropped buffers, corrupted buffers, disconnect).
#include "hal/v4l2_capture.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <vector>

#include "tests/hal/hil_devices.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra::hal {
namespace {

V4l2CaptureConfig v4l2_config(const std::string& device, int w, int h,
                              std::initializer_list<PixelFormat> formats = {PixelFormat::grey}) {
  V4l2CaptureConfig c;
  std::snprintf(c.device.data(), c.device.size(), "%s", device.c_str());
  c.width = w;
  c.height = h;
  for (PixelFormat f : formats) EXPECT_TRUE(c.formats.push_back(f));
  c.buffers = 4;
  // vivid under emulation skips frame times when its thread runs late: only the
  // test about gaps treats them as faults.
  c.gaps_are_faults = false;
  return c;
}

TEST(V4l2CaptureConfig, EveryBadFieldIsNamed) {
  V4l2Capture cam;
  EXPECT_EQ(cam.open(v4l2_config("", 640, 480)).code(), Errc::missing_field);
  EXPECT_EQ(cam.open(v4l2_config("/dev/video0", 0, 480)).code(), Errc::invalid_argument);
  EXPECT_EQ(cam.open(v4l2_config("/dev/video0", 640, 480, {})).code(), Errc::missing_field);
  auto few = v4l2_config("/dev/video0", 640, 480);
  few.buffers = 1;
  EXPECT_EQ(cam.open(few).code(), Errc::invalid_argument);
  few.buffers = V4l2Capture::kMaxBuffers + 1;
  EXPECT_EQ(cam.open(few).code(), Errc::invalid_argument);
  EXPECT_FALSE(cam.is_open());
  EXPECT_EQ(cam.next(10).code(), Errc::not_ready);
  EXPECT_EQ(cam.start().code(), Errc::not_ready);
}

TEST(V4l2CaptureConfig, MissingDevicesAndNonCamerasAreIoErrors) {
  V4l2Capture cam;
  auto by_name = cam.open(v4l2_config("no-such-camera", 640, 480));
  ASSERT_FALSE(by_name.ok());
  EXPECT_EQ(by_name.code(), Errc::io_error);
  EXPECT_NE(std::strstr(by_name.error().message, "no-such-camera"), nullptr);
  auto by_path = cam.open(v4l2_config("/dev/no-such-video", 640, 480));
  EXPECT_EQ(by_path.code(), Errc::io_error);
  auto not_v4l2 = cam.open(v4l2_config("/dev/null", 640, 480));
  ASSERT_FALSE(not_v4l2.ok());
  EXPECT_NE(std::strstr(not_v4l2.error().message, "QUERYCAP"), nullptr) << not_v4l2.error().message;
}

class V4l2OnVivid : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = test::video_path(test::vivid_left());
    if (path_.empty())
      GTEST_SKIP() << "skipped: no V4L2 node named '" << test::vivid_left()
                   << "' (the HIL bench loads vivid)";
  }
  void TearDown() override {
    if (!path_.empty()) {  // leave the device as we found it
      test::set_v4l2_control(path_, "Percentage of Dropped Buffers", 0);
      test::set_v4l2_control(path_, "OSD Text Mode", 0);
    }
  }
  std::string path_;
};

TEST_F(V4l2OnVivid, StreamsCheckedGreyFramesWithoutHeap) {
  V4l2Capture cam;
  auto s = cam.open(v4l2_config(test::vivid_left(), 640, 480));  // by name
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_STREQ(cam.path(), path_.c_str());
  EXPECT_EQ(cam.format().pixel, PixelFormat::grey);
  EXPECT_GE(cam.buffer_count(), 2);
  ASSERT_TRUE(cam.start().ok());
  std::uint32_t last_seq = 0;
  std::int64_t last_t = 0;
  long distinct = 0;
  test::HeapScope heap;
  for (int i = 0; i < 10; ++i) {
    auto f = test::next_frame(cam, 2000);
    ASSERT_TRUE(f.ok()) << f.error().message;
    EXPECT_EQ(f->bytes_used, 640u * 480u);
    if (i > 0) {
      EXPECT_GT(f->sequence, last_seq);
      EXPECT_GT(f->time_ns, last_t);
    }
    last_seq = f->sequence;
    last_t = f->time_ns;
    // vivid draws a test pattern: not a constant image.
    for (std::uint32_t k = 1; k < f->bytes_used; k += 97) distinct += f->data[k] != f->data[0];
  }
  EXPECT_EQ(heap.allocations(), 0u);
  EXPECT_GT(distinct, 0);
  EXPECT_EQ(cam.health().frames, 10u);
  EXPECT_EQ(cam.health().rejected, 0u);
}

TEST_F(V4l2OnVivid, NegotiatesEachFormatAndConvertsToTheSameLuma) {
  // vivid prints counters and times over the image: off, so frames compare.
  ASSERT_TRUE(test::set_v4l2_control(path_, "OSD Text Mode", 2));
  std::vector<std::uint8_t> reference(640 * 480);
  for (PixelFormat f : {PixelFormat::grey, PixelFormat::y16, PixelFormat::yuyv}) {
    SCOPED_TRACE(pixel_format_name(f));
    V4l2Capture cam;
    auto s = cam.open(v4l2_config(path_, 640, 480, {f}));  // by path
    ASSERT_TRUE(s.ok()) << s.error().message;
    EXPECT_EQ(cam.format().pixel, f);
    EXPECT_GE(cam.format().bytes_per_line, 640u * static_cast<unsigned>(bytes_per_pixel(f)));
    ASSERT_TRUE(cam.start().ok());
    auto frame = test::next_frame(cam, 2000);
    ASSERT_TRUE(frame.ok()) << frame.error().message;
    std::vector<std::uint8_t> gray(640 * 480);
    ASSERT_TRUE(convert_to_gray(*frame, cam.format(), 0, Gray8View(gray.data(), 640, 480)).ok());
    if (f == PixelFormat::grey) {
      reference = gray;
      continue;
    }
    // The same 75 % colour bars in another container. Coloured bars differ by
    // the luma weights of each encoding (vivid's GREY is not Rec. 601), but the
    // white and black bars are the same in any encoding (R = G = B), and every
    // bar edge is at the same column.
    long worst = 0;
    for (int y = 0; y < 480; ++y)
      for (int x : {0, 40, 79, 560, 600, 639}) {
        const std::size_t i = static_cast<std::size_t>(y * 640 + x);
        worst = std::max(worst, std::labs(long{gray[i]} - long{reference[i]}));
      }
    EXPECT_LE(worst, 2) << "white or black bar differs from GREY";
    for (int x = 1; x < 640; ++x) {
      const std::size_t i = static_cast<std::size_t>(240 * 640 + x);
      const bool edge = std::labs(long{gray[i]} - long{gray[i - 1]}) > 2;
      const bool ref_edge = std::labs(long{reference[i]} - long{reference[i - 1]}) > 2;
      EXPECT_EQ(edge, ref_edge) << "bar edge at column " << x;
    }
  }
}

TEST_F(V4l2OnVivid, SetsASupportedFrameRateAndRefusesOthers) {
  V4l2Capture cam;
  auto c = v4l2_config(path_, 640, 480);
  c.fps = 25;
  auto s = cam.open(c);
  EXPECT_TRUE(s.ok()) << s.error().message;
  c.fps = 7;  // vivid offers 1, 2, 4, 5, 10, 12.5, 15, 25 at 640x480
  auto bad = cam.open(c);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(std::strstr(bad.error().message, "configured 7"), nullptr) << bad.error().message;
}

TEST_F(V4l2OnVivid, PrefersTheFirstOfferedFormat) {
  V4l2Capture cam;
  ASSERT_TRUE(cam.open(v4l2_config(path_, 640, 480, {PixelFormat::yuyv, PixelFormat::grey})).ok());
  EXPECT_EQ(cam.format().pixel, PixelFormat::yuyv);
}

TEST_F(V4l2OnVivid, ASizeTheDriverChangesIsRefused) {
  V4l2Capture cam;
  auto s = cam.open(v4l2_config(path_, 1000, 700));
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.code(), Errc::invalid_argument);
  EXPECT_NE(std::strstr(s.error().message, "configured 1000x700"), nullptr) << s.error().message;
  EXPECT_FALSE(cam.is_open());
}

TEST_F(V4l2OnVivid, NoFrameIsATimeoutAndStreamingResumesAfter) {
  V4l2Capture cam;
  ASSERT_TRUE(cam.open(v4l2_config(path_, 640, 480)).ok());
  ASSERT_TRUE(cam.start().ok());
  ASSERT_TRUE(test::next_frame(cam, 2000).ok());
  ASSERT_TRUE(test::set_v4l2_control(path_, "Percentage of Dropped Buffers", 100));
  (void)cam.flush();
  auto none = cam.next(300);
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.code(), Errc::timeout);
  EXPECT_NE(std::strstr(none.error().message, "no frame within 300 ms"), nullptr)
      << none.error().message;
  EXPECT_EQ(cam.health().last_fault, FrameFault::timeout);
  EXPECT_EQ(cam.health().timeouts, 1u);
  ASSERT_TRUE(test::set_v4l2_control(path_, "Percentage of Dropped Buffers", 0));
  (void)cam.flush();
  auto back = test::next_frame(cam, 2000);
  EXPECT_TRUE(back.ok()) << back.error().message;
}

TEST_F(V4l2OnVivid, ACorruptedBufferIsRejectedAndTheNextFrameIsFine) {
  V4l2Capture cam;
  ASSERT_TRUE(cam.open(v4l2_config(path_, 640, 480)).ok());
  ASSERT_TRUE(cam.start().ok());
  ASSERT_TRUE(test::next_frame(cam, 2000).ok());
  ASSERT_TRUE(test::set_v4l2_control(path_, "Inject V4L2_BUF_FLAG_ERROR", 1));
  bool rejected = false;
  for (int i = 0; i < 8 && !rejected; ++i) {
    auto f = test::next_frame(cam, 2000);
    if (!f.ok()) {
      EXPECT_EQ(f.code(), Errc::parse_error) << f.error().message;
      EXPECT_NE(std::strstr(f.error().message, "corrupted"), nullptr) << f.error().message;
      rejected = true;
    }
  }
  ASSERT_TRUE(rejected) << "the injected error never arrived";
  EXPECT_EQ(cam.health().last_fault, FrameFault::driver_error);
  EXPECT_GE(cam.health().rejected, 1u);  // plus any vivid repeat skipped on the way
  auto next = test::next_frame(cam, 2000);
  EXPECT_TRUE(next.ok()) << next.error().message;
}

TEST_F(V4l2OnVivid, LostFramesAreASequenceGap) {
  V4l2Capture cam;
  auto c = v4l2_config(path_, 640, 480);
  c.gaps_are_faults = true;
  ASSERT_TRUE(cam.open(c).ok());
  ASSERT_TRUE(cam.start().ok());
  ASSERT_TRUE(test::next_frame(cam, 2000).ok());
  ASSERT_TRUE(test::set_v4l2_control(path_, "Percentage of Dropped Buffers", 50));
  bool gap = false;
  for (int i = 0; i < 30 && !gap; ++i) {
    auto f = test::next_frame(cam, 3000);
    if (!f.ok()) {
      ASSERT_EQ(f.code(), Errc::parse_error) << f.error().message;
      EXPECT_NE(std::strstr(f.error().message, "sequence gap"), nullptr) << f.error().message;
      gap = true;
    }
  }
  EXPECT_TRUE(gap) << "30 frames at 50 % drop and no gap";
  EXPECT_EQ(cam.health().last_fault, FrameFault::sequence_gap);
}

// Last: vivid's disconnect is for good, so it uses the spare instance.
TEST(V4l2OnVividSpare, ADisconnectedCameraEndsAsDeviceLost) {
  const std::string spare = test::video_path(test::vivid_spare());
  if (spare.empty())
    GTEST_SKIP() << "skipped: no V4L2 node named '" << test::vivid_spare()
                 << "' (the HIL bench loads vivid)";
  V4l2Capture cam;
  ASSERT_TRUE(cam.open(v4l2_config(spare, 640, 480)).ok());
  ASSERT_TRUE(cam.start().ok());
  ASSERT_TRUE(test::next_frame(cam, 2000).ok());
  ASSERT_TRUE(test::set_v4l2_control(spare, "Disconnect", 1));
  Result<RawFrame> f = test::next_frame(cam, 2000);
  for (int i = 0; i < 8 && f.ok(); ++i)
    f = test::next_frame(cam, 2000);  // frames already done may still come
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(f.code(), Errc::io_error) << f.error().message;
  EXPECT_EQ(cam.health().last_fault, FrameFault::device_lost) << f.error().message;
  cam.close();  // unmapping and closing a vanished device is clean
}

}  // namespace
}  // namespace petra::hal
