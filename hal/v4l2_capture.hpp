// One V4L2 capture device with mmap streaming (the rover's cameras, vivid in
// the HIL bench). open() resolves the device by path or by the name under
// /sys/class/video4linux/*/name, picks the first configured pixel format the
// device offers, sets the size, and maps a fixed number of buffers; after
// open() nothing allocates. next() waits for a frame with a timeout, checks it
// (hal/video_frame.hpp) and holds its buffer until the next call.
// Errors: Errc::timeout (no frame in time), Errc::io_error (device gone,
// stream stopped, ioctl refused), Errc::parse_error (a broken frame, see
// FrameFault), config errors naming the field.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "algo/core/fixed_vector.hpp"
#include "algo/core/result.hpp"
#include "hal/frame_source.hpp"
#include "hal/video_frame.hpp"

namespace petra::hal {

struct V4l2CaptureConfig {
  static constexpr std::size_t kMaxName = 64;
  // "/dev/video3" (starts with '/') or a node name such as "vivid-000-vid-cap".
  std::array<char, kMaxName> device{};
  int width = 0;  // px, what the calibration is for
  int height = 0;
  // Preference order; the first one the device offers is used.
  FixedVector<PixelFormat, kPixelFormatCount> formats;
  int buffers = 4;  // mmap buffers requested (2..V4l2Capture::kMaxBuffers)
  int fps = 0;      // frames per second to set; 0 keeps the driver's rate
  // Lost frames (sequence gaps) are errors; off for a free-running camera that
  // is read now and then (they are still counted in CameraHealth::frames_lost).
  bool gaps_are_faults = true;
};

// Finds the /dev/videoN node whose /sys/class/video4linux/videoN/name is `name`.
Status find_video_node(const char* name, std::array<char, V4l2CaptureConfig::kMaxName>& path);

class V4l2Capture final : public FrameSource {
 public:
  static constexpr int kMaxBuffers = 8;

  V4l2Capture() = default;
  V4l2Capture(const V4l2Capture&) = delete;
  V4l2Capture& operator=(const V4l2Capture&) = delete;
  ~V4l2Capture() override;

  Status open(const V4l2CaptureConfig& config);
  Status start();  // STREAMON with every buffer queued
  Status stop();   // STREAMOFF; buffers are queued again by the next start()
  void close();
  bool is_open() const { return fd_ >= 0; }
  bool streaming() const { return streaming_; }

  // Next frame within timeout_ms (the previously returned frame is given back
  // first). The frame's data stays valid until the next next()/flush()/stop().
  Result<RawFrame> next(int timeout_ms) override;
  // Gives back every frame already waiting, so the next frame is a fresh one,
  // and starts a new sequence run (frames lost while nobody was reading are
  // not faults). Returns how many frames were dropped.
  Result<int> flush() override;

  const FrameFormat& format() const override { return format_; }
  const CameraHealth& health() const override { return health_; }
  const char* path() const { return path_.data(); }
  const char* card() const { return card_.data(); }
  int buffer_count() const { return buffer_count_; }

 private:
  Status requeue_held();
  Status dequeue(RawFrame& out, bool& got);
  Error fail_device(const char* what, int err);
  // open()'s steps; each closes the device when it fails.
  static Status check_config(const V4l2CaptureConfig& config);
  Status open_capture_node();
  Result<PixelFormat> choose_format(const V4l2CaptureConfig& config);
  Status set_format(const V4l2CaptureConfig& config, PixelFormat chosen);
  Status set_frame_rate(const V4l2CaptureConfig& config);
  Status map_buffers(const V4l2CaptureConfig& config);

  int fd_ = -1;
  bool streaming_ = false;
  int held_ = -1;  // index of the buffer given out by next(), -1 when none
  int buffer_count_ = 0;
  std::array<std::uint8_t*, kMaxBuffers> memory_{};
  std::array<std::size_t, kMaxBuffers> length_{};
  std::array<char, V4l2CaptureConfig::kMaxName> path_{};
  std::array<char, 32> card_{};
  FrameFormat format_{};
  bool gaps_are_faults_ = true;
  FrameChecker checker_;
  CameraHealth health_;
};

}  // namespace petra::hal
