// The camera and gpio sections of the flight configuration: a full example,
// the defaults, and an error naming the field for each kind of bad value.
#include "hal/device_config.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <string>

namespace petra::hal {
namespace {

struct Parsed {
  std::array<json::Token, 128> tokens{};
  std::string text;
};

template <class F>
auto with_doc(const std::string& text, F f) {
  Parsed p;
  p.text = text;
  auto doc = json::Document::parse(p.text, p.tokens);
  EXPECT_TRUE(doc.ok()) << (doc.ok() ? "" : doc.error().message);
  return f(*doc);
}

Result<V4l2CameraSection> camera(const std::string& body) {
  return with_doc("{" + body + "}",
                  [](const json::Document& d) { return parse_v4l2_camera(d, 0); });
}
Result<GpioSection> gpio(const std::string& body) {
  return with_doc("{" + body + "}", [](const json::Document& d) { return parse_gpio(d, 0); });
}

TEST(DeviceConfig, AFullCameraSection) {
  auto c = camera(
      R"("kind":"v4l2","layout":"two_devices","left":"vivid-000-vid-cap","right":"/dev/video1",
         "width":640,"height":480,"formats":["YUYV","GREY"],"buffers":6,"fps":25,
         "timeout_ms":500,"max_skew_us":20000,"max_pair_frames":5,"triggered":true,
         "trigger_width_us":250)");
  ASSERT_TRUE(c.ok()) << c.error().message;
  const V4l2StereoConfig& s = c->config;
  EXPECT_STREQ(s.left.device.data(), "vivid-000-vid-cap");
  EXPECT_STREQ(s.right.device.data(), "/dev/video1");
  EXPECT_EQ(s.timing.layout, StereoLayout::two_devices);
  EXPECT_EQ(s.timing.width, 640);
  EXPECT_EQ(s.timing.height, 480);
  ASSERT_EQ(s.left.formats.size(), 2u);
  EXPECT_EQ(s.left.formats[0], PixelFormat::yuyv);
  EXPECT_EQ(s.right.formats[1], PixelFormat::grey);
  EXPECT_EQ(s.right.buffers, 6);
  EXPECT_EQ(s.right.fps, 25);
  EXPECT_EQ(s.timing.timeout_ms, 500);
  EXPECT_EQ(s.timing.max_skew_us, 20000);
  EXPECT_EQ(s.timing.max_pair_frames, 5);
  EXPECT_EQ(s.timing.trigger_width_us, 250u);
  EXPECT_TRUE(c->triggered);
}

TEST(DeviceConfig, DefaultsForAOneCameraLayout) {
  auto c = camera(R"("layout":"side_by_side","left":"cam","width":320,"height":240)");
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->config.timing.layout, StereoLayout::side_by_side);
  ASSERT_EQ(c->config.left.formats.size(), 1u);
  EXPECT_EQ(c->config.left.formats[0], PixelFormat::grey);
  EXPECT_EQ(c->config.left.buffers, 4);
  EXPECT_EQ(c->config.timing.timeout_ms, 1000);
  EXPECT_FALSE(c->triggered);
}

TEST(DeviceConfig, EachBadCameraFieldIsNamed) {
  const std::pair<const char*, const char*> cases[] = {
      {R"("right":"r","width":640,"height":480)", "camera.left: missing"},
      {R"("left":"l","width":640,"height":480)", "camera.right: missing"},
      {R"("left":"l","right":"r","height":480)", "camera.width/height: missing"},
      {R"("left":"l","right":"r","width":640.5,"height":480)", "camera.width: expected a whole"},
      {R"("left":"l","right":"r","width":640,"height":480,"layout":"stacked")",
       "camera.layout 'stacked'"},
      {R"("left":"l","right":"r","width":640,"height":480,"formats":["MJPG"])",
       "camera.formats[0]: pixel format 'MJPG'"},
      {R"("left":"l","right":"r","width":640,"height":480,"formats":"GREY")", "camera.formats:"},
      {R"("left":"l","right":"r","width":640,"height":480,"buffers":1)", "camera.buffers:"},
      {R"("left":"l","right":"r","width":640,"height":480,"max_skew_us":-1)",
       "camera.max_skew_us:"},
      {R"("left":"l","right":"r","width":640,"height":480,"triggered":1)",
       "camera.triggered: expected true or false"},
      {R"("left":"","right":"r","width":640,"height":480)", "camera.left: length 0"},
  };
  for (const auto& [body, words] : cases) {
    auto c = camera(body);
    ASSERT_FALSE(c.ok()) << body;
    EXPECT_NE(std::strstr(c.error().message, words), nullptr)
        << body << " -> " << c.error().message;
  }
}

TEST(DeviceConfig, GpioLinesByNameOrObject) {
  auto g = gpio(R"("chip":"petra-hil","trigger":"cam_trigger",
                   "estop":{"line":"estop","active_low":true},
                   "arm_power":{"chip":"gpiochip3","line":"pwr"})");
  ASSERT_TRUE(g.ok()) << g.error().message;
  EXPECT_TRUE(g->has_trigger);
  EXPECT_STREQ(g->trigger.chip.data(), "petra-hil");
  EXPECT_STREQ(g->trigger.line.data(), "cam_trigger");
  EXPECT_FALSE(g->trigger.active_low);
  EXPECT_TRUE(g->estop.active_low);
  EXPECT_STREQ(g->estop.chip.data(), "petra-hil");
  EXPECT_STREQ(g->arm_power.chip.data(), "gpiochip3");
  EXPECT_STREQ(g->arm_power.line.data(), "pwr");
  auto none = gpio(R"("chip":"c")");
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none->has_trigger || none->has_arm_power || none->has_estop);
}

TEST(DeviceConfig, EachBadGpioFieldIsNamed) {
  const std::pair<const char*, const char*> cases[] = {
      {R"("estop":"estop")", "gpio.estop: no chip"},
      {R"("chip":"c","estop":5)", "gpio.estop: expected a line name or an object"},
      {R"("chip":"c","estop":{"active_low":true})", "gpio.estop.line: missing"},
      {R"("chip":"c","trigger":{"line":"t","active_low":"yes"})",
       "gpio.trigger.active_low: expected true or false"},
      {R"("chip":"c","arm_power":"a-name-that-is-much-too-long-for-a-line")",
       "gpio.arm_power: line name length"},
  };
  for (const auto& [body, words] : cases) {
    auto g = gpio(body);
    ASSERT_FALSE(g.ok()) << body;
    EXPECT_NE(std::strstr(g.error().message, words), nullptr)
        << body << " -> " << g.error().message;
  }
}

}  // namespace
}  // namespace petra::hal
