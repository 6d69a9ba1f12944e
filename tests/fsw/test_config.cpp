#include "fsw/config.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace petra::fsw {
namespace {

Result<FswConfig> parse(const std::string& s) {
  return parse_config(s.data(), s.size(), "/etc/petra");
}

const std::string kMinimal = R"({"uplink":{"key_file":"k.hex"},"camera":{"dir":"/data/pairs"}})";

TEST(Config, MinimalFileGetsDefaultsAndResolvesRelativePaths) {
  auto c = parse(kMinimal);
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_STREQ(c->key_file.data(), "/etc/petra/k.hex");
  EXPECT_STREQ(c->camera_dir.data(), "/data/pairs");
  EXPECT_EQ(c->cmd_port, 47100);
  EXPECT_EQ(c->tlm_port, 47101);
  EXPECT_EQ(c->cycle_ms, 10u);
  EXPECT_EQ(c->budget.image_width, 1024);
}

TEST(Config, EveryErrorNamesTheField) {
  const struct {
    const char* text;
    const char* names;
  } cases[] = {
      {R"({"camera":{"dir":"x"}})", "uplink"},
      {R"({"uplink":{},"camera":{"dir":"x"}})", "uplink.key_file"},
      {R"({"uplink":{"key_file":"k","port":70000},"camera":{"dir":"x"}})", "uplink.port"},
      {R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},"loop":{"cycle_ms":0}})",
       "loop.cycle_ms"},
      {R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},"budget":{"arena_mb":"big"}})",
       "budget.arena_mb"},
      {R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},"budget":{"roi_width":512}})",
       "budget.roi_height"},
      {R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},"budget":{"roi_width":8}})",
       "budget.roi_width"},
      {R"({"uplink":{"key_file":"k"},"camera":{"kind":"usb","dir":"x"}})", "camera.kind"},
      {R"({"uplink":{"key_file":"k"},"camera":{"kind":"v4l2","left":"a","right":"b"}})",
       "camera.width"},
      {R"({"uplink":{"key_file":"k"},"camera":{"kind":"v4l2","left":"a","width":64,"height":48}})",
       "camera.right"},
      {R"({"uplink":{"key_file":"k"},"camera":{"kind":"v4l2","left":"a","right":"b","width":64,"height":48,"fps":5000}})",
       "camera.fps"},
      {R"({"uplink":{"key_file":"k"},"camera":{"kind":"v4l2","left":"a","right":"b","width":64,"height":48,"triggered":true}})",
       "gpio.trigger"},
      {R"({"uplink":{"key_file":"k"},"camera":{"kind":"libcamera","right":"b","width":64,"height":48}})",
       "camera.left"},
      {R"({"uplink":{"key_file":"k"},"camera":{"kind":"libcamera","left":"a","width":64,"height":48}})",
       "camera.right"},
      {R"({"uplink":{"key_file":"k"},"camera":{"kind":"libcamera","left":"a","layout":"side_by_side"}})",
       "camera.width"},
      {R"({"uplink":{"key_file":"k"},"camera":{"kind":"libcamera","left":"a","layout":"stacked","width":64,"height":48}})",
       "camera.layout"},
      {R"({"uplink":{"key_file":"k"},"camera":{"kind":"libcamera","left":"a","layout":"side_by_side","width":64,"height":48,"formats":["GREY","Y16"]}})",
       "camera.formats[1]: Y16"},
      {R"({"uplink":{"key_file":"k"},"camera":{"kind":"libcamera","left":"a","layout":"side_by_side","width":64,"height":48,"buffers":9}})",
       "camera.buffers"},
      {R"({"uplink":{"key_file":"k"},"camera":{"kind":"libcamera","left":"a","layout":"side_by_side","width":64,"height":48,"triggered":true}})",
       "gpio.trigger"},
      {R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},"gpio":{"estop":"estop"}})",
       "gpio.estop"},
      {R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},"gpio":{"chip":"c","arm_power":7}})",
       "gpio.arm_power"},
      {R"({"uplink":{"key_file":"k"}})", "camera"},
      {R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},)", "json"},
      {R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},"arm":{"can_interface":"udp:1:0"}})",
       "arm.can_interface 'udp:1:0'"},
  };
  for (const auto& c : cases) {
    auto r = parse(c.text);
    ASSERT_FALSE(r.ok()) << c.text;
    EXPECT_NE(std::string(r.error().message).find(c.names), std::string::npos)
        << r.error().message << " should name " << c.names;
  }
}

// A misspelt key would leave its default flying: every section refuses keys
// it does not know, naming the key and the section.
TEST(Config, UnknownKeysAreRefusedByName) {
  const struct {
    const char* text;
    const char* names;
  } cases[] = {
      {R"({"upink":{"key_file":"k"},"uplink":{"key_file":"k"},"camera":{"dir":"x"}})",
       "config: upink: unknown key"},
      {R"({"uplink":{"key_file":"k","prot":47100},"camera":{"dir":"x"}})",
       "config: uplink.prot: unknown key"},
      {R"({"uplink":{"key_file":"k"},"downlink":{"hots":"1.2.3.4"},"camera":{"dir":"x"}})",
       "downlink.hots"},
      {R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},"loop":{"cycle":5}})", "loop.cycle"},
      {R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},"budget":{"arena":5}})", "budget.arena"},
      {R"({"uplink":{"key_file":"k"},"camera":{"dir":"x","width":64}})", "camera.width"},
      {R"({"uplink":{"key_file":"k"},"camera":{"kind":"v4l2","left":"a","right":"b","width":64,"height":48,"fsp":5}})",
       "camera.fsp"},
      {R"({"uplink":{"key_file":"k"},"camera":{"kind":"libcamera","left":"a","right":"b","width":64,"height":48,"fps":25}})",
       "camera.fps"},
      {R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},"arm":{"can_interface":"can0","mnt":[0,0,0,0]}})",
       "arm.mnt"},
      {R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},"gpio":{"chip":"c","e_stop":"x"}})",
       "gpio.e_stop"},
      {R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},"gpio":{"chip":"c","estop":{"line":"x","active_high":true}}})",
       "gpio.estop.active_high"},
  };
  for (const auto& c : cases) {
    auto r = parse(c.text);
    ASSERT_FALSE(r.ok()) << c.text;
    EXPECT_NE(std::string(r.error().message).find(c.names), std::string::npos)
        << r.error().message << " should name " << c.names;
    EXPECT_NE(std::string(r.error().message).find("expected one of"), std::string::npos)
        << r.error().message;
  }
}

TEST(Config, ArmOnCanOverUdpKeepsTheSpec) {
  auto c = parse(
      R"({"uplink":{"key_file":"k"},"camera":{"dir":"x"},"arm":{"can_interface":"udp:47200:47201","mount":[300,100,100,90]}})");
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_TRUE(c->arm.enabled);
  EXPECT_STREQ(c->arm.can_interface.data(), "udp:47200:47201");
}

TEST(Config, AV4l2CameraAndTheGpioLinesAreReadForTheDevices) {
  auto c = parse(R"({"uplink":{"key_file":"k"},
      "camera":{"kind":"v4l2","left":"vivid-000-vid-cap","right":"vivid-001-vid-cap",
                "width":640,"height":480,"formats":["YUYV","GREY"],"fps":25,"timeout_ms":500,
                "max_skew_us":20000,"triggered":true},
      "gpio":{"chip":"petra-hil","trigger":"cam_trigger","arm_power":"arm_power",
              "estop":{"line":"estop","active_low":true}},
      "arm":{"can_interface":"vcan0"}})");
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->camera_kind, CameraKind::v4l2);
  EXPECT_STREQ(c->v4l2.config.left.device.data(), "vivid-000-vid-cap");
  EXPECT_STREQ(c->v4l2.config.right.device.data(), "vivid-001-vid-cap");
  EXPECT_EQ(c->v4l2.config.timing.width, 640);
  EXPECT_EQ(c->v4l2.config.timing.timeout_ms, 500);
  EXPECT_EQ(c->v4l2.config.left.fps, 25);
  EXPECT_TRUE(c->v4l2.triggered);
  EXPECT_TRUE(c->gpio.has_trigger && c->gpio.has_arm_power && c->gpio.has_estop);
  EXPECT_STREQ(c->gpio.estop.chip.data(), "petra-hil");
  EXPECT_STREQ(c->gpio.estop.line.data(), "estop");
  EXPECT_TRUE(c->gpio.estop.active_low);
  EXPECT_FALSE(c->gpio.arm_power.active_low);
  EXPECT_STREQ(c->arm.can_interface.data(), "vcan0");
  // Without a gpio section nothing is wired; a file camera stays the default.
  auto plain = parse(kMinimal);
  ASSERT_TRUE(plain.ok());
  EXPECT_EQ(plain->camera_kind, CameraKind::file);
  EXPECT_FALSE(plain->gpio.has_estop || plain->gpio.has_arm_power || plain->gpio.has_trigger);
}

// The HIL bench's libcamera camera (vimc, one sensor carrying both views side
// by side): the fields reach the libcamera backend's configuration.
TEST(Config, ALibcameraCameraIsReadForTheDevices) {
  auto c = parse(R"({"uplink":{"key_file":"k"},
      "camera":{"kind":"libcamera","layout":"side_by_side","left":"Sensor B",
                "width":636,"height":480,"formats":["GREY","YUYV"],"buffers":6,
                "timeout_ms":2000,"max_skew_us":40000,"max_pair_frames":16}})");
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->camera_kind, CameraKind::libcamera);
  const hal::LibcameraStereoConfig& lc = c->libcamera.config;
  EXPECT_EQ(lc.timing.layout, hal::StereoLayout::side_by_side);
  EXPECT_STREQ(lc.left.camera.data(), "Sensor B");
  EXPECT_EQ(lc.timing.width, 636);
  EXPECT_EQ(lc.timing.height, 480);
  ASSERT_EQ(lc.left.formats.size(), 2u);
  EXPECT_EQ(lc.left.formats[0], hal::PixelFormat::grey);
  EXPECT_EQ(lc.left.formats[1], hal::PixelFormat::yuyv);
  EXPECT_EQ(lc.left.buffers, 6);
  EXPECT_EQ(lc.timing.timeout_ms, 2000);
  EXPECT_EQ(lc.timing.max_skew_us, 40000);
  EXPECT_EQ(lc.timing.max_pair_frames, 16);
  EXPECT_FALSE(c->libcamera.triggered);
  // Two cameras, triggered through the gpio line.
  auto two = parse(R"({"uplink":{"key_file":"k"},
      "camera":{"kind":"libcamera","left":"Sensor A","right":"Sensor B","width":64,"height":48,
                "triggered":true},
      "gpio":{"chip":"petra-hil","trigger":"cam_trigger"}})");
  ASSERT_TRUE(two.ok()) << two.error().message;
  EXPECT_EQ(two->libcamera.config.timing.layout, hal::StereoLayout::two_devices);
  EXPECT_STREQ(two->libcamera.config.right.camera.data(), "Sensor B");
  EXPECT_EQ(two->libcamera.config.right.formats.size(), 1u);  // GREY, as the left
  EXPECT_TRUE(two->libcamera.triggered);
}

// Relative paths resolve against the file's folder: a path too long for the
// folder's buffer is an error naming it, not a cut folder.
TEST(Config, AFilePathTooLongForItsFolderIsRefused) {
  namespace fs = std::filesystem;
  const fs::path root = fs::temp_directory_path() / "petra_config_long_path";
  const fs::path dir = root / std::string(120, 'a') / std::string(120, 'b') / std::string(40, 'c');
  fs::create_directories(dir);
  const fs::path file = dir / "fsw.json";
  std::ofstream(file) << kMinimal;
  ASSERT_GT(file.string().size(), 255u);
  auto c = load_config(file.c_str());
  ASSERT_FALSE(c.ok());
  EXPECT_NE(std::string(c.error().message).find("config path"), std::string::npos)
      << c.error().message;
  // The same content under a short path loads.
  const fs::path near = root / "fsw.json";
  std::ofstream(near) << kMinimal;
  auto ok = load_config(near.c_str());
  EXPECT_TRUE(ok.ok()) << (ok.ok() ? "" : ok.error().message);
  fs::remove_all(root);
}

TEST(Config, TheCounterFloorIsOptionalAndBounded) {
  auto plain = parse(kMinimal);
  ASSERT_TRUE(plain.ok());
  EXPECT_EQ(plain->counter_floor, -1);      // none: a missing counter file stops the start
  EXPECT_EQ(plain->counter_file[0], '\0');  // none named: beside the key
  EXPECT_EQ(plain->commands_per_cycle, 32u);
  auto floor =
      parse(R"({"uplink":{"key_file":"k","counter_floor":4294967295},"camera":{"dir":"d"}})");
  ASSERT_TRUE(floor.ok()) << floor.error().message;
  EXPECT_EQ(floor->counter_floor, 4294967295);
  for (const char* bad : {"-1", "4294967296", "1.5", "\"7\""}) {
    auto r = parse(std::string(R"({"uplink":{"key_file":"k","counter_floor":)") + bad +
                   R"(},"camera":{"dir":"d"}})");
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_NE(std::string(r.error().message).find("uplink.counter_floor"), std::string::npos);
  }
}

}  // namespace
}  // namespace petra::fsw
