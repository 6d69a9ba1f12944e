// One camera through libcamera (optional at build time: PETRA_WITH_LIBCAMERA,
// Debian's libcamera-dev 0.0.3): the same FrameSource as the V4L2 backend, so
// the stereo assembly and the frame checks are shared. open() starts the
// camera manager, acquires and configures the camera, allocates and maps every
// buffer and creates one request per buffer; next() only re-queues a request
// and waits for a completed one.
// Memory: Petra's side allocates nothing after open(); libcamera itself
// allocates inside queueRequest() and its completion path (measured in the
// HIL bench and stated in docs/hal.md).
// Built without libcamera: libcamera_available() is false and open() fails
// with Errc::not_ready.
#pragma once

#include <array>
#include <cstddef>
#include <memory>

#include "algo/core/fixed_vector.hpp"
#include "hal/frame_source.hpp"

namespace petra::hal {

bool libcamera_available();

struct LibcameraCaptureConfig {
  static constexpr std::size_t kMaxId = 128;
  // A substring of the camera id ("Sensor B", "platform/vimc.0"); "" = the first camera.
  std::array<char, kMaxId> camera{};
  int width = 0;
  int height = 0;
  FixedVector<PixelFormat, kPixelFormatCount> formats;  // preference order
  int buffers = 4;                                      // 2..LibcameraCapture::kMaxBuffers
  bool gaps_are_faults = true;
};

class LibcameraCapture final : public FrameSource {
 public:
  static constexpr int kMaxBuffers = 8;

  LibcameraCapture();
  LibcameraCapture(const LibcameraCapture&) = delete;
  LibcameraCapture& operator=(const LibcameraCapture&) = delete;
  ~LibcameraCapture() override;

  Status open(const LibcameraCaptureConfig& config);
  Status start();
  Status stop();
  void close();
  bool is_open() const;

  Result<RawFrame> next(int timeout_ms) override;
  Result<int> flush() override;
  const FrameFormat& format() const override { return format_; }
  const CameraHealth& health() const override { return health_; }
  const char* camera_id() const { return id_.data(); }

 private:
  struct Impl;  // libcamera objects, kept out of this header
  // open()'s steps; each closes the camera when it fails.
  Status acquire_camera(const LibcameraCaptureConfig& cfg);
  Status configure_stream(const LibcameraCaptureConfig& cfg);
  Status map_requests();
  void abandon();  // close() of a camera stop() could not stop
  std::unique_ptr<Impl> impl_;
  FrameFormat format_{};
  CameraHealth health_;
  std::array<char, LibcameraCaptureConfig::kMaxId> id_{};
};

}  // namespace petra::hal
