// Assembling one stereo pair from frame sources, whatever the backend: two
// cameras (left, right) or one camera carrying both views side by side (2W x H)
// or pixel-interleaved (W x H, two bytes a pixel: left, right; a
// Bumblebee2-class camera).
//   free running (no trigger): stale frames are flushed; the next frames are
//     paired by timestamp, reading the older side again (at most
//     max_pair_frames per side) until |t_left - t_right| <= max_skew.
//   triggered: the trigger line is pulsed once (both cameras); the next frame
//     of each must be within max_skew, else the pair is refused.
// Output: 8-bit gray views of width x height. No heap.
#pragma once

#include <cstdint>

#include "hal/frame_source.hpp"
#include "hal/gpio.hpp"

namespace petra::hal {

enum class StereoLayout : std::uint8_t { two_devices, side_by_side, pixel_interleaved };
const char* stereo_layout_name(StereoLayout layout);

struct StereoTiming {
  StereoLayout layout = StereoLayout::two_devices;
  int width = 0;  // px, one view
  int height = 0;
  int timeout_ms = 1000;  // per frame
  std::int64_t max_skew_us = 1000;
  int max_pair_frames = 8;        // free running: frames read per side to find a pair
  GpioOutput* trigger = nullptr;  // set: triggered mode
  std::uint32_t trigger_width_us = 100;
};
Status check_stereo_timing(const StereoTiming& t);

struct StereoFrameInfo {
  std::uint32_t sequence = 0;     // pairs delivered since open, the first is 1
  std::int64_t left_time_ns = 0;  // CLOCK_MONOTONIC
  std::int64_t right_time_ns = 0;
  std::uint32_t left_sequence = 0;  // the drivers' frame counters
  std::uint32_t right_sequence = 0;
  std::uint32_t frames_skipped = 0;  // frames read but not paired (free running)
};

struct StereoHealth {
  std::uint32_t pairs = 0;
  std::uint32_t skew_failures = 0;
  FrameFault last_fault = FrameFault::none;
};

// One pair into left/right (both t.width x t.height). `right` is null for the
// one-camera layouts. Faults are counted in `health`.
Result<StereoFrameInfo> assemble_pair(const StereoTiming& t, FrameSource& left, FrameSource* right,
                                      Gray8View left_view, Gray8View right_view,
                                      StereoHealth& health);

}  // namespace petra::hal
