// Video frames as a capture device delivers them, before they become the
// pipeline's 8-bit gray images: the pixel formats Petra accepts, the format a
// device negotiated, the checks every frame passes (size, driver error flag,
// sequence, timestamp) and the conversion to gray. Pure code, no OS calls, no
// heap: shared by the V4L2 and libcamera backends and tested on the host.
#pragma once

#include <cstdint>
#include <string_view>

#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"

namespace petra::hal {

// GREY: 8-bit luma. Y16: 16-bit little-endian luma (the top 8 bits are kept).
// YUYV: 4:2:2 packed, luma at every even byte (chroma is dropped).
// RGB24 / BGR24: 3 bytes a pixel in that memory order (what libcamera's vimc
// and many ISPs give); gray = Rec. 601 luma (77 R + 150 G + 29 B) / 256.
enum class PixelFormat : std::uint8_t { grey, y16, yuyv, rgb24, bgr24 };
inline constexpr int kPixelFormatCount = 5;

const char* pixel_format_name(PixelFormat f);
// V4L2 fourcc code of the format ('GREY', 'Y16 ', 'YUYV', 'RGB3', 'BGR3').
std::uint32_t pixel_format_fourcc(PixelFormat f);
Result<PixelFormat> pixel_format_from_name(std::string_view name);
Result<PixelFormat> pixel_format_from_fourcc(std::uint32_t fourcc);
int bytes_per_pixel(PixelFormat f);

// What a device delivers after negotiation.
struct FrameFormat {
  PixelFormat pixel = PixelFormat::grey;
  int width = 0;                     // px
  int height = 0;                    // px
  std::uint32_t bytes_per_line = 0;  // >= width * bytes_per_pixel
  std::uint32_t image_bytes = 0;     // >= bytes_per_line * height
  // Luma coded 16..235 (video range, usual for YUYV) rather than 0..255: the
  // conversion to gray stretches it back to full range.
  bool limited_range = false;
};

// Checks what a driver answered to a format request: the size must be the one
// asked for (the calibration is for that size) and the line and image sizes must
// hold the pixels. Errors name the field and both values.
Status check_negotiated(const FrameFormat& got, PixelFormat want_pixel, int want_width,
                        int want_height);

// One dequeued buffer. `data` stays valid until the buffer is given back.
struct RawFrame {
  const std::uint8_t* data = nullptr;
  std::uint32_t bytes_used = 0;
  std::uint32_t sequence = 0;  // driver's frame counter
  std::int64_t time_ns = 0;    // capture time, CLOCK_MONOTONIC
  bool driver_error = false;   // the driver flagged the buffer as corrupted
};

// Why a frame was rejected (the last one is kept in CameraHealth).
enum class FrameFault : std::uint8_t {
  none,
  driver_error,         // V4L2_BUF_FLAG_ERROR / libcamera FrameError
  wrong_size,           // bytes used differ from the negotiated image size
  sequence_gap,         // frames were lost between this one and the previous
  sequence_backwards,   // the counter went back (driver restart)
  timestamp_backwards,  // capture time not after the previous frame's
  timeout,              // no frame within the timeout
  device_lost,          // the device vanished or stopped streaming
  skew,                 // stereo: no left/right pair within the allowed skew
};
const char* frame_fault_name(FrameFault f);

// Counters for housekeeping, per device.
struct CameraHealth {
  std::uint32_t frames = 0;       // frames accepted
  std::uint32_t rejected = 0;     // frames refused by FrameChecker
  std::uint32_t frames_lost = 0;  // sum of sequence gaps
  std::uint32_t timeouts = 0;
  std::uint32_t device_errors = 0;
  FrameFault last_fault = FrameFault::none;
};

// Checks each frame against the negotiated format and the previous frame.
// A rejected frame still becomes the reference for the next one, so one fault
// gives one error, not a cascade. Lost frames (a sequence gap) are a fault when
// every frame matters (triggered capture); a free-running camera read only now
// and then loses frames by design, so there gaps are only counted.
class FrameChecker {
 public:
  void reset(const FrameFormat& format, bool gaps_are_faults = true) {
    format_ = format;
    gaps_are_faults_ = gaps_are_faults;
    have_previous_ = false;
    lost_ = 0;
  }
  // Ok, or an error (Errc::parse_error) naming the fault; `fault` says which.
  Status check(const RawFrame& frame, FrameFault& fault);
  // Frames lost between the previous frame and the one last checked.
  std::uint32_t lost() const { return lost_; }

 private:
  FrameFormat format_{};
  bool gaps_are_faults_ = true;
  bool have_previous_ = false;
  std::uint32_t lost_ = 0;
  std::uint32_t last_sequence_ = 0;
  std::int64_t last_time_ns_ = 0;
};

// Converts the region of a frame starting at column x0 (in pixels) and as wide
// and high as `out` into 8-bit full-range gray. The region must lie inside the frame.
Status convert_to_gray(const RawFrame& frame, const FrameFormat& format, int x0, Gray8View out);

// A pixel-interleaved stereo frame (2 bytes per pixel: byte 0 left, byte 1
// right, the layout of a Bumblebee2-class camera) split into two gray views of
// the frame's width and height.
Status deinterleave_pair(const RawFrame& frame, const FrameFormat& format, Gray8View left,
                         Gray8View right);

}  // namespace petra::hal
