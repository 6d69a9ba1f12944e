// Stereo pairs from V4L2. Configuration errors everywhere; pairs from two
// vivid instances (free running, paired by timestamp within the allowed skew)
// and from one device carrying both views (side by side, pixel-interleaved)
// in the HIL guest, skipped on hosts without the devices.
#include "hal/v4l2_stereo_camera.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "hal/device_config.hpp"
#include "hal/gpio_sim.hpp"
#include "hal/stereo_pairing.hpp"
#include "tests/hal/hil_devices.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra::hal {
namespace {

void set_device(V4l2CaptureConfig& c, const std::string& device,
                std::initializer_list<PixelFormat> formats) {
  std::snprintf(c.device.data(), c.device.size(), "%s", device.c_str());
  c.formats.clear();
  for (PixelFormat f : formats) EXPECT_TRUE(c.formats.push_back(f));
}

V4l2StereoConfig two_vivids(std::int64_t max_skew_us) {
  V4l2StereoConfig c;
  c.timing.layout = StereoLayout::two_devices;
  set_device(c.left, test::vivid_left(), {PixelFormat::grey});
  set_device(c.right, test::vivid_right(), {PixelFormat::grey});
  c.left.fps = c.right.fps = 25;  // vivid's fastest rate at 640x480: a 40 ms period
  c.timing.width = 640;
  c.timing.height = 480;
  c.timing.timeout_ms = 2000;
  c.timing.max_skew_us = max_skew_us;
  return c;
}

TEST(V4l2StereoConfig, BadSettingsAreRefusedBeforeAnyDeviceIsOpened) {
  V4l2StereoCamera cam;
  auto c = two_vivids(1000);
  c.timing.width = 0;
  EXPECT_EQ(cam.open(c).code(), Errc::invalid_argument);
  c = two_vivids(-1);
  EXPECT_EQ(cam.open(c).code(), Errc::invalid_argument);
  c = two_vivids(1000);
  c.timing.timeout_ms = 0;
  EXPECT_EQ(cam.open(c).code(), Errc::invalid_argument);
  c = two_vivids(1000);
  c.timing.max_pair_frames = 0;
  EXPECT_EQ(cam.open(c).code(), Errc::invalid_argument);
  c = two_vivids(1000);
  c.timing.layout = StereoLayout::pixel_interleaved;  // GREY cannot carry two views
  auto s = cam.open(c);
  EXPECT_EQ(s.code(), Errc::invalid_argument);
  EXPECT_NE(std::strstr(s.error().message, "2-byte"), nullptr) << s.error().message;
  std::vector<std::uint8_t> px(640 * 480);
  EXPECT_EQ(cam.acquire(Gray8View(px.data(), 640, 480), Gray8View(px.data(), 640, 480)).code(),
            Errc::not_ready);
}

class StereoOnVivid : public ::testing::Test {
 protected:
  void SetUp() override {
    if (test::video_path(test::vivid_left()).empty() ||
        test::video_path(test::vivid_right()).empty())
      GTEST_SKIP() << "skipped: no V4L2 nodes '" << test::vivid_left() << "' and '"
                   << test::vivid_right() << "' (the HIL bench loads vivid)";
  }
  std::vector<std::uint8_t> l_ = std::vector<std::uint8_t>(640 * 480);
  std::vector<std::uint8_t> r_ = std::vector<std::uint8_t>(640 * 480);
  Gray8View left() { return Gray8View(l_.data(), 640, 480); }
  Gray8View right() { return Gray8View(r_.data(), 640, 480); }
};

TEST_F(StereoOnVivid, TwoFreeRunningCamerasArePairedWithinTheSkew) {
  // Two vivid instances at 25 frames/s with an arbitrary phase: a skew bound
  // over half the 40 ms period can always be met.
  V4l2StereoCamera cam;
  auto s = cam.open(two_vivids(25'000));
  ASSERT_TRUE(s.ok()) << s.error().message;
  std::uint32_t last_seq = 0;
  test::HeapScope heap;
  for (int i = 0; i < 5; ++i) {
    auto info = test::acquire_pair(cam, left(), right());
    ASSERT_TRUE(info.ok()) << info.error().message;
    EXPECT_LE(abs_skew_ns(info->left_time_ns, info->right_time_ns), 25'000'000);
    EXPECT_EQ(info->sequence, last_seq + 1);
    last_seq = info->sequence;
  }
  EXPECT_EQ(heap.allocations(), 0u);
  EXPECT_EQ(cam.health().pairs, 5u);
  long differs = 0;
  for (std::size_t k = 0; k < l_.size(); k += 101) differs += l_[k] != l_[0];
  EXPECT_GT(differs, 0) << "left view is blank";
}

TEST_F(StereoOnVivid, AZeroSkewBoundIsEnforcedAndARefusalNamesTheSkew) {
  V4l2StereoCamera cam;
  auto c = two_vivids(0);
  c.timing.max_pair_frames = 3;
  ASSERT_TRUE(cam.open(c).ok());
  auto info = test::acquire_pair(cam, left(), right());
  if (info.ok()) {
    // Two free-running vivid instances can stamp a frame at the same instant
    // (one kernel timer drives both): a pair is then correct only if its
    // stamps are equal. Usually they are not and the pair is refused.
    EXPECT_EQ(info->left_time_ns, info->right_time_ns);
    return;
  }
  EXPECT_EQ(info.code(), Errc::timeout);
  EXPECT_NE(std::strstr(info.error().message, "no pair within 0 us"), nullptr)
      << info.error().message;
  EXPECT_EQ(cam.health().last_fault, FrameFault::skew);
  EXPECT_EQ(cam.health().skew_failures, 1u);
}

TEST_F(StereoOnVivid, TriggeredPairPulsesTheTriggerOnce) {
  SimGpioOutput trigger;
  V4l2StereoCamera cam;
  auto c = two_vivids(20'000);
  c.timing.trigger = &trigger;
  c.timing.trigger_width_us = 200;
  ASSERT_TRUE(cam.open(c).ok());
  auto info = test::acquire_pair(cam, left(), right());
  EXPECT_EQ(trigger.rising_edges(), 1u);
  EXPECT_EQ(trigger.falling_edges(), 1u);
  // vivid free-runs whatever the trigger: the pair is accepted only if the
  // first frames happen to fall within the bound, else refused as skew.
  if (!info.ok()) {
    EXPECT_EQ(cam.health().last_fault, FrameFault::skew) << info.error().message;
  }
}

TEST_F(StereoOnVivid, SideBySideFrameIsSplitIntoTwoViews) {
  // One device 1280x720 carrying two 640x720 views.
  V4l2StereoConfig c;
  c.timing.layout = StereoLayout::side_by_side;
  set_device(c.left, test::vivid_left(), {PixelFormat::grey});
  c.timing.width = 640;
  c.timing.height = 720;
  V4l2StereoCamera cam;
  auto s = cam.open(c);
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(cam.left_capture().format().width, 1280);
  std::vector<std::uint8_t> l(640 * 720), r(640 * 720);
  auto info = test::acquire_pair(cam, Gray8View(l.data(), 640, 720), Gray8View(r.data(), 640, 720));
  ASSERT_TRUE(info.ok()) << info.error().message;
  EXPECT_EQ(info->left_time_ns, info->right_time_ns);
  EXPECT_NE(l, r) << "vivid's colour bars differ between the two halves";
}

TEST_F(StereoOnVivid, PixelInterleavedFrameIsSplitByteWise) {
  V4l2StereoConfig c;
  c.timing.layout = StereoLayout::pixel_interleaved;
  set_device(c.left, test::vivid_left(), {PixelFormat::grey, PixelFormat::y16});
  c.timing.width = 640;
  c.timing.height = 480;
  V4l2StereoCamera cam;
  auto s = cam.open(c);
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(cam.left_capture().format().pixel, PixelFormat::y16);
  auto info = test::acquire_pair(cam, left(), right());
  ASSERT_TRUE(info.ok()) << info.error().message;
  // Right = high bytes of vivid's Y16 = its 8-bit luma: a pattern, not blank.
  long differs = 0;
  for (std::size_t k = 0; k < r_.size(); k += 101) differs += r_[k] != r_[0];
  EXPECT_GT(differs, 0);
}

TEST_F(StereoOnVivid, OpensFromTheConfigurationAndStampsPairsInRealTime) {
  const std::string text = "{\"kind\":\"v4l2\",\"left\":\"" + test::vivid_left() +
                           "\",\"right\":\"" + test::vivid_right() +
                           "\",\"width\":640,\"height\":480,\"formats\":[\"GREY\"],"
                           "\"fps\":25,\"max_skew_us\":25000,\"timeout_ms\":2000}";
  std::array<json::Token, 64> tokens{};
  auto doc = json::Document::parse(text, tokens);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  auto section = parse_v4l2_camera(*doc, 0);
  ASSERT_TRUE(section.ok()) << section.error().message;
  V4l2StereoCamera cam;
  auto s = cam.open(section->config);
  ASSERT_TRUE(s.ok()) << s.error().message;
  StereoCamera& generic = cam;  // the executive's interface
  EXPECT_STREQ(generic.name(), "v4l2");
  auto meta = test::acquire_pair(cam, left(), right());
  ASSERT_TRUE(meta.ok()) << meta.error().message;
  timespec now{};
  clock_gettime(CLOCK_REALTIME, &now);
  const std::int64_t now_ns = static_cast<std::int64_t>(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
  // vivid stamps the expected end of the frame, which may lie a few ms ahead.
  EXPECT_LT(meta->left_time_ns, now_ns + 1'000'000'000);
  EXPECT_GT(meta->left_time_ns, now_ns - 10'000'000'000);  // taken within the last 10 s
  EXPECT_EQ(meta->sequence, 1u);
  EXPECT_EQ(cam.last_info().left_sequence, meta->source_index);
}

}  // namespace
}  // namespace petra::hal
