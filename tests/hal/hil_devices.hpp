// Test-side helpers for the device tests that run for real inside the HIL
// guest (sim/hil): the bench's board (vivid cameras, a gpio-sim chip) and the
// knobs the tests turn from outside (vivid's fault-injection controls, the
// gpio-sim pull of an input, the level of an output). On a host without the
// devices the tests skip and say why. Test code: may allocate.
#pragma once

#include <fcntl.h>
#include <linux/gpio.h>
#include <linux/videodev2.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "hal/v4l2_capture.hpp"
#include "hal/v4l2_stereo_camera.hpp"

namespace petra::test {

inline std::string env_or(const char* name, const char* fallback) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' ? v : fallback;
}

// The bench loads vivid with three capture-only instances: 0 and 1 are the
// stereo pair, 2 is the one the tests may disconnect.
inline std::string vivid_left() {
  return env_or("PETRA_TEST_V4L2_LEFT", "vivid-000-vid-cap");
}
inline std::string vivid_right() {
  return env_or("PETRA_TEST_V4L2_RIGHT", "vivid-001-vid-cap");
}
inline std::string vivid_spare() {
  return env_or("PETRA_TEST_V4L2_SPARE", "vivid-002-vid-cap");
}
// The bench's gpio-sim bank label and line names.
inline std::string gpio_chip() {
  return env_or("PETRA_TEST_GPIO_CHIP", "petra-hil");
}

// "/dev/videoN" for a node name, or "" when there is none.
inline std::string video_path(const std::string& name) {
  std::array<char, hal::V4l2CaptureConfig::kMaxName> path{};
  if (!hal::find_video_node(name.c_str(), path).ok()) return "";
  return path.data();
}

// vivid under emulation now and then runs its frame tick twice for one frame
// time and hands out two buffers with the same sequence number; FrameChecker
// rightly refuses the repeat (sequence_backwards). Tests that are not about
// that check take the next frame instead (at most 3 times).
inline Result<hal::RawFrame> next_frame(hal::V4l2Capture& cam, int timeout_ms) {
  auto f = cam.next(timeout_ms);
  for (int i = 0;
       i < 3 && !f.ok() && cam.health().last_fault == hal::FrameFault::sequence_backwards; ++i)
    f = cam.next(timeout_ms);
  return f;
}
inline Result<hal::FrameMeta> acquire_pair(hal::V4l2StereoCamera& cam, Gray8View left,
                                           Gray8View right) {
  auto f = cam.acquire(left, right);
  for (int i = 0;
       i < 3 && !f.ok() && cam.health().last_fault == hal::FrameFault::sequence_backwards; ++i)
    f = cam.acquire(left, right);
  return f;
}

// Sets a control by its name ("Percentage of Dropped Buffers", "Disconnect").
// Buttons take any value. Returns false when the device has no such control.
inline bool set_v4l2_control(const std::string& device_path, const char* name, int value) {
  const int fd = ::open(device_path.c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) return false;
  v4l2_queryctrl q{};
  q.id = V4L2_CTRL_FLAG_NEXT_CTRL;
  bool done = false;
  while (!done && ::ioctl(fd, VIDIOC_QUERYCTRL, &q) == 0) {
    if (std::strcmp(reinterpret_cast<const char*>(q.name), name) == 0) {
      v4l2_control c{};
      c.id = q.id;
      c.value = value;
      done = ::ioctl(fd, VIDIOC_S_CTRL, &c) == 0;
      break;
    }
    q.id |= V4L2_CTRL_FLAG_NEXT_CTRL;
  }
  ::close(fd);
  return done;
}

// A gpio chip found by label through the character device (no libgpiod needed).
struct GpioChipInfo {
  std::string name;  // "gpiochip1"
  int lines = 0;
};
inline GpioChipInfo find_gpio_chip(const std::string& label) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const auto& dev : fs::directory_iterator("/dev", ec)) {
    const std::string n = dev.path().filename().string();
    if (n.rfind("gpiochip", 0) != 0) continue;
    const int fd = ::open(dev.path().c_str(), O_RDWR | O_CLOEXEC);
    if (fd < 0) continue;
    gpiochip_info info{};
    const bool ok = ::ioctl(fd, GPIO_GET_CHIPINFO_IOCTL, &info) == 0;
    ::close(fd);
    if (ok && label == info.label) return {n, static_cast<int>(info.lines)};
  }
  return {};
}

// Offset of the line called `line` on /dev/<chip>, -1 when none.
inline int gpio_line_offset(const std::string& chip, const char* line) {
  const int fd = ::open(("/dev/" + chip).c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) return -1;
  int found = -1;
  for (unsigned i = 0; i < 64 && found < 0; ++i) {
    gpio_v2_line_info info{};
    info.offset = i;
    if (::ioctl(fd, GPIO_V2_GET_LINEINFO_IOCTL, &info) != 0) break;
    if (std::strcmp(info.name, line) == 0) found = static_cast<int>(i);
  }
  ::close(fd);
  return found;
}

// The gpio-sim side of a chip: /sys/devices/platform/gpio-sim.N/gpiochipM.
inline std::string gpio_sim_dir(const std::string& chip_name) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const auto& dev : fs::directory_iterator("/sys/devices/platform", ec)) {
    if (dev.path().filename().string().rfind("gpio-sim.", 0) != 0) continue;
    const fs::path p = dev.path() / chip_name;
    if (fs::exists(p / "sim_gpio0", ec)) return p.string();
  }
  return "";
}

inline bool write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
  return static_cast<bool>(f);
}

inline std::string read_text(const std::string& path) {
  std::ifstream f(path);
  std::string s;
  std::getline(f, s);
  return s;
}

}  // namespace petra::test
