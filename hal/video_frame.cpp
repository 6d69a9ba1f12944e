#include "hal/video_frame.hpp"

namespace petra::hal {

namespace {

constexpr std::uint32_t fourcc(char a, char b, char c, char d) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(a)) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b)) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(c)) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(d)) << 24;
}

constexpr PixelFormat kAll[kPixelFormatCount] = {
    PixelFormat::grey, PixelFormat::y16, PixelFormat::yuyv, PixelFormat::rgb24, PixelFormat::bgr24};

std::uint64_t pixel_bytes(const FrameFormat& f) {
  return static_cast<std::uint64_t>(f.bytes_per_line) * static_cast<std::uint64_t>(f.height);
}

}  // namespace

const char* pixel_format_name(PixelFormat f) {
  switch (f) {
    case PixelFormat::grey:
      return "GREY";
    case PixelFormat::y16:
      return "Y16";
    case PixelFormat::yuyv:
      return "YUYV";
    case PixelFormat::rgb24:
      return "RGB24";
    case PixelFormat::bgr24:
      return "BGR24";
  }
  return "?";
}

std::uint32_t pixel_format_fourcc(PixelFormat f) {
  switch (f) {
    case PixelFormat::grey:
      return fourcc('G', 'R', 'E', 'Y');
    case PixelFormat::y16:
      return fourcc('Y', '1', '6', ' ');
    case PixelFormat::yuyv:
      return fourcc('Y', 'U', 'Y', 'V');
    case PixelFormat::rgb24:
      return fourcc('R', 'G', 'B', '3');
    case PixelFormat::bgr24:
      return fourcc('B', 'G', 'R', '3');
  }
  return 0;
}

Result<PixelFormat> pixel_format_from_name(std::string_view name) {
  for (PixelFormat f : kAll)
    if (name == pixel_format_name(f)) return f;
  return Error::make(Errc::invalid_argument,
                     "pixel format '%.*s': expected GREY, Y16, YUYV, RGB24 or BGR24",
                     static_cast<int>(name.size() > 16 ? 16 : name.size()), name.data());
}

Result<PixelFormat> pixel_format_from_fourcc(std::uint32_t code) {
  for (PixelFormat f : kAll)
    if (code == pixel_format_fourcc(f)) return f;
  return Error::make(Errc::invalid_argument, "pixel format %08x is not one Petra reads", code);
}

int bytes_per_pixel(PixelFormat f) {
  switch (f) {
    case PixelFormat::grey:
      return 1;
    case PixelFormat::y16:
    case PixelFormat::yuyv:
      return 2;
    case PixelFormat::rgb24:
    case PixelFormat::bgr24:
      return 3;
  }
  return 1;
}

const char* frame_fault_name(FrameFault f) {
  switch (f) {
    case FrameFault::none:
      return "none";
    case FrameFault::driver_error:
      return "driver_error";
    case FrameFault::wrong_size:
      return "wrong_size";
    case FrameFault::sequence_gap:
      return "sequence_gap";
    case FrameFault::sequence_backwards:
      return "sequence_backwards";
    case FrameFault::timestamp_backwards:
      return "timestamp_backwards";
    case FrameFault::timeout:
      return "timeout";
    case FrameFault::device_lost:
      return "device_lost";
    case FrameFault::skew:
      return "skew";
  }
  return "?";
}

Status check_negotiated(const FrameFormat& got, PixelFormat want_pixel, int want_width,
                        int want_height) {
  if (got.pixel != want_pixel)
    return Error::make(Errc::wrong_type, "format: device gives %s, asked for %s",
                       pixel_format_name(got.pixel), pixel_format_name(want_pixel));
  if (got.width != want_width || got.height != want_height)
    return Error::make(Errc::invalid_argument, "format: device gives %dx%d, configured %dx%d",
                       got.width, got.height, want_width, want_height);
  const std::uint64_t min_line = static_cast<std::uint64_t>(got.width) *
                                 static_cast<std::uint64_t>(bytes_per_pixel(got.pixel));
  if (got.bytes_per_line < min_line)
    return Error::make(Errc::invalid_argument,
                       "format: bytes_per_line %u cannot hold %d %s pixels (%llu bytes)",
                       got.bytes_per_line, got.width, pixel_format_name(got.pixel),
                       static_cast<unsigned long long>(min_line));
  if (got.image_bytes < pixel_bytes(got))
    return Error::make(Errc::invalid_argument, "format: image_bytes %u < %u lines of %u bytes",
                       got.image_bytes, static_cast<unsigned>(got.height), got.bytes_per_line);
  return ok_status();
}

Status FrameChecker::check(const RawFrame& frame, FrameFault& fault) {
  fault = FrameFault::none;
  lost_ = 0;
  const bool had_previous = have_previous_;
  const std::uint32_t prev_seq = last_sequence_;
  const std::int64_t prev_time = last_time_ns_;
  have_previous_ = true;
  last_sequence_ = frame.sequence;
  last_time_ns_ = frame.time_ns;

  if (frame.driver_error) {
    fault = FrameFault::driver_error;
    return Error::make(Errc::parse_error, "frame %u: the driver flagged the buffer as corrupted",
                       frame.sequence);
  }
  if (frame.data == nullptr || frame.bytes_used < pixel_bytes(format_) ||
      frame.bytes_used > format_.image_bytes) {
    fault = FrameFault::wrong_size;
    return Error::make(Errc::parse_error, "frame %u: %u bytes, a %dx%d %s image needs %llu",
                       frame.sequence, frame.bytes_used, format_.width, format_.height,
                       pixel_format_name(format_.pixel),
                       static_cast<unsigned long long>(pixel_bytes(format_)));
  }
  if (!had_previous) return ok_status();
  // Counters are 32-bit and wrap: compare modulo 2^32 (half the range counts as "back").
  const std::uint32_t step = frame.sequence - prev_seq;
  if (step == 0 || step > 0x80000000u) {
    fault = FrameFault::sequence_backwards;
    return Error::make(Errc::parse_error, "frame %u: sequence went back (previous %u)",
                       frame.sequence, prev_seq);
  }
  if (frame.time_ns <= prev_time) {
    fault = FrameFault::timestamp_backwards;
    return Error::make(Errc::parse_error,
                       "frame %u: timestamp %lld ns is not after the previous frame's (%lld ns)",
                       frame.sequence, static_cast<long long>(frame.time_ns),
                       static_cast<long long>(prev_time));
  }
  if (step != 1) {
    lost_ = step - 1;
    if (!gaps_are_faults_) return ok_status();
    fault = FrameFault::sequence_gap;
    return Error::make(Errc::parse_error, "frame %u: sequence gap, %u frame(s) lost after %u",
                       frame.sequence, step - 1, prev_seq);
  }
  return ok_status();
}

Status convert_to_gray(const RawFrame& frame, const FrameFormat& format, int x0, Gray8View out) {
  if (x0 < 0 || out.width() <= 0 || out.height() <= 0 || x0 + out.width() > format.width ||
      out.height() > format.height)
    return Error::make(Errc::out_of_range, "convert: region x0=%d %dx%d outside the %dx%d frame",
                       x0, out.width(), out.height(), format.width, format.height);
  if (frame.data == nullptr || frame.bytes_used < pixel_bytes(format))
    return Error::make(Errc::invalid_argument, "convert: frame holds %u bytes, needs %llu",
                       frame.bytes_used, static_cast<unsigned long long>(pixel_bytes(format)));
  const int bpp = bytes_per_pixel(format.pixel);
  if (bpp == 3) {
    const bool rgb = format.pixel == PixelFormat::rgb24;
    for (int y = 0; y < out.height(); ++y) {
      const std::uint8_t* src = frame.data + static_cast<std::size_t>(y) * format.bytes_per_line +
                                static_cast<std::size_t>(x0) * 3;
      std::uint8_t* dst = out.row(y);
      for (int x = 0; x < out.width(); ++x, src += 3) {
        const unsigned r = rgb ? src[0] : src[2];
        const unsigned b = rgb ? src[2] : src[0];
        dst[x] = static_cast<std::uint8_t>((77 * r + 150 * src[1] + 29 * b + 128) >> 8);
      }
    }
    return ok_status();
  }
  // Y16 is little-endian: the high byte is the second one. YUYV: luma first.
  const int pick = format.pixel == PixelFormat::y16 ? 1 : 0;
  // Video range 16..235 -> 0..255, rounded and clamped (a 256-entry table on the stack).
  std::uint8_t stretch[256];
  for (int v = 0; v < 256; ++v) {
    int g = v;
    if (format.limited_range) g = ((v - 16) * 255 + 109) / 219;
    stretch[v] = static_cast<std::uint8_t>(g < 0 ? 0 : (g > 255 ? 255 : g));
  }
  for (int y = 0; y < out.height(); ++y) {
    const std::uint8_t* src = frame.data + static_cast<std::size_t>(y) * format.bytes_per_line +
                              static_cast<std::size_t>(x0) * static_cast<std::size_t>(bpp) +
                              static_cast<std::size_t>(pick);
    std::uint8_t* dst = out.row(y);
    for (int x = 0; x < out.width(); ++x) dst[x] = stretch[src[static_cast<std::size_t>(x * bpp)]];
  }
  return ok_status();
}

Status deinterleave_pair(const RawFrame& frame, const FrameFormat& format, Gray8View left,
                         Gray8View right) {
  if (bytes_per_pixel(format.pixel) != 2)
    return Error::make(Errc::wrong_type, "deinterleave: %s has one byte per pixel, need two",
                       pixel_format_name(format.pixel));
  if (left.width() != format.width || left.height() != format.height ||
      right.width() != format.width || right.height() != format.height)
    return Error::make(Errc::invalid_argument,
                       "deinterleave: views %dx%d and %dx%d, frame is %dx%d", left.width(),
                       left.height(), right.width(), right.height(), format.width, format.height);
  if (frame.data == nullptr || frame.bytes_used < pixel_bytes(format))
    return Error::make(Errc::invalid_argument, "deinterleave: frame holds %u bytes, needs %llu",
                       frame.bytes_used, static_cast<unsigned long long>(pixel_bytes(format)));
  for (int y = 0; y < format.height; ++y) {
    const std::uint8_t* src = frame.data + static_cast<std::size_t>(y) * format.bytes_per_line;
    std::uint8_t* l = left.row(y);
    std::uint8_t* r = right.row(y);
    for (int x = 0; x < format.width; ++x) {
      l[x] = src[2 * x];
      r[x] = src[2 * x + 1];
    }
  }
  return ok_status();
}

}  // namespace petra::hal
