#include "hal/device_config.hpp"

#include <cmath>
#include <cstdio>

namespace petra::hal {

namespace {

using json::Type;

// Copies a string field into a fixed buffer; absent is fine unless required.
template <std::size_t N>
Status text(const json::Document& doc, std::uint32_t obj, const char* section, const char* key,
            std::array<char, N>& out, bool required) {
  const std::uint32_t i = doc.find(obj, key);
  if (i == 0) {
    if (required) return Error::make(Errc::missing_field, "%s.%s: missing", section, key);
    return ok_status();
  }
  if (doc.token(i).type != Type::string)
    return Error::make(Errc::wrong_type, "%s.%s: expected a string, got %s", section, key,
                       json::type_name(doc.token(i).type));
  const std::string_view s = doc.text_of(i);
  if (s.empty() || s.size() >= N)
    return Error::make(Errc::invalid_argument, "%s.%s: length %zu outside 1..%zu", section, key,
                       s.size(), N - 1);
  (void)std::snprintf(out.data(), N, "%.*s", static_cast<int>(s.size()), s.data());
  return ok_status();
}

// A whole number in lo..hi; absent keeps `out`.
template <class T>
Status integer(const json::Document& doc, std::uint32_t obj, const char* section, const char* key,
               double lo, double hi, T& out) {
  const std::uint32_t i = doc.find(obj, key);
  if (i == 0) return ok_status();
  if (doc.token(i).type != Type::number)
    return Error::make(Errc::wrong_type, "%s.%s: expected a number, got %s", section, key,
                       json::type_name(doc.token(i).type));
  const double v = doc.token(i).number;
  if (v != std::floor(v) || v < lo || v > hi)
    return Error::make(Errc::invalid_argument, "%s.%s: expected a whole number %g..%g, got %g",
                       section, key, lo, hi, v);
  out = static_cast<T>(v);
  return ok_status();
}

Status boolean(const json::Document& doc, std::uint32_t obj, const char* section, const char* key,
               bool& out) {
  const std::uint32_t i = doc.find(obj, key);
  if (i == 0) return ok_status();
  if (doc.token(i).type != Type::boolean)
    return Error::make(Errc::wrong_type, "%s.%s: expected true or false", section, key);
  out = doc.token(i).number != 0.0;
  return ok_status();
}

Status gpio_line(const json::Document& doc, std::uint32_t obj, const char* key,
                 const std::array<char, GpioLineConfig::kMaxName>& chip, GpioLineConfig& out,
                 bool& present) {
  const std::uint32_t i = doc.find(obj, key);
  present = i != 0;
  if (!present) return ok_status();
  out = GpioLineConfig{};
  out.chip = chip;
  char section[32];
  (void)std::snprintf(section, sizeof section, "gpio.%s", key);
  if (doc.token(i).type == Type::string) {
    const std::string_view s = doc.text_of(i);
    if (s.empty() || s.size() >= out.line.size())
      return Error::make(Errc::invalid_argument, "%s: line name length %zu outside 1..%zu", section,
                         s.size(), out.line.size() - 1);
    (void)std::snprintf(out.line.data(), out.line.size(), "%.*s", static_cast<int>(s.size()),
                        s.data());
  } else if (doc.token(i).type == Type::object) {
    PETRA_TRY(text(doc, i, section, "chip", out.chip, false));
    PETRA_TRY(text(doc, i, section, "line", out.line, true));
    PETRA_TRY(boolean(doc, i, section, "active_low", out.active_low));
  } else {
    return Error::make(Errc::wrong_type, "%s: expected a line name or an object", section);
  }
  if (out.chip[0] == '\0')
    return Error::make(Errc::missing_field, "%s: no chip (set gpio.chip or %s.chip)", section,
                       section);
  return ok_status();
}

}  // namespace

namespace {

Status layout_field(const json::Document& doc, std::uint32_t obj, StereoTiming& t) {
  std::array<char, 24> layout{};
  PETRA_TRY(text(doc, obj, "camera", "layout", layout, false));
  const std::string_view l = layout.data();
  if (l.empty() || l == "two_devices")
    t.layout = StereoLayout::two_devices;
  else if (l == "side_by_side")
    t.layout = StereoLayout::side_by_side;
  else if (l == "pixel_interleaved")
    t.layout = StereoLayout::pixel_interleaved;
  else
    return Error::make(Errc::invalid_argument,
                       "camera.layout '%s': expected two_devices, side_by_side or "
                       "pixel_interleaved",
                       layout.data());
  return ok_status();
}

// The fields both camera backends share after the layout and the camera
// names: view size, formats, buffers, timing and the trigger.
Status stereo_fields(const json::Document& doc, std::uint32_t obj, int max_buffers, StereoTiming& t,
                     FixedVector<PixelFormat, kPixelFormatCount>& formats, int& buffers,
                     bool& triggered) {
  t.width = 0;
  t.height = 0;
  PETRA_TRY(integer(doc, obj, "camera", "width", 1, 8192, t.width));
  PETRA_TRY(integer(doc, obj, "camera", "height", 1, 8192, t.height));
  if (t.width == 0 || t.height == 0)
    return Error::make(Errc::missing_field, "camera.width/height: missing");

  const std::uint32_t list = doc.find(obj, "formats");
  if (list == 0) {
    (void)formats.push_back(PixelFormat::grey);
  } else {
    if (doc.token(list).type != Type::array || doc.token(list).count == 0 ||
        doc.token(list).count > kPixelFormatCount)
      return Error::make(Errc::wrong_type, "camera.formats: expected 1..%d format names",
                         kPixelFormatCount);
    for (std::uint32_t k = 0; k < doc.token(list).count; ++k) {
      const std::uint32_t e = doc.element(list, k);
      if (doc.token(e).type != Type::string)
        return Error::make(Errc::wrong_type, "camera.formats[%u]: expected a name", k);
      auto f = pixel_format_from_name(doc.text_of(e));
      if (!f) return Error::make(f.code(), "camera.formats[%u]: %s", k, f.error().message);
      (void)formats.push_back(*f);
    }
  }
  PETRA_TRY(integer(doc, obj, "camera", "buffers", 2, max_buffers, buffers));
  PETRA_TRY(integer(doc, obj, "camera", "timeout_ms", 1, 60000, t.timeout_ms));
  PETRA_TRY(integer(doc, obj, "camera", "max_skew_us", 0, 1000000, t.max_skew_us));
  PETRA_TRY(integer(doc, obj, "camera", "max_pair_frames", 1, 64, t.max_pair_frames));
  PETRA_TRY(integer(doc, obj, "camera", "trigger_width_us", 1, 1000000, t.trigger_width_us));
  PETRA_TRY(boolean(doc, obj, "camera", "triggered", triggered));
  return ok_status();
}

}  // namespace

Result<V4l2CameraSection> parse_v4l2_camera(const json::Document& doc, std::uint32_t obj) {
  if (doc.token(obj).type != Type::object)
    return Error::make(Errc::wrong_type, "camera: expected an object");
  V4l2CameraSection out;
  V4l2StereoConfig& c = out.config;
  StereoTiming& t = c.timing;
  PETRA_TRY(layout_field(doc, obj, t));
  PETRA_TRY(text(doc, obj, "camera", "left", c.left.device, true));
  PETRA_TRY(
      text(doc, obj, "camera", "right", c.right.device, t.layout == StereoLayout::two_devices));
  PETRA_TRY(stereo_fields(doc, obj, V4l2Capture::kMaxBuffers, t, c.left.formats, c.left.buffers,
                          out.triggered));
  PETRA_TRY(integer(doc, obj, "camera", "fps", 0, 1000, c.left.fps));
  c.right.formats = c.left.formats;
  c.right.buffers = c.left.buffers;
  c.right.fps = c.left.fps;
  return out;
}

Result<LibcameraCameraSection> parse_libcamera_camera(const json::Document& doc,
                                                      std::uint32_t obj) {
  if (doc.token(obj).type != Type::object)
    return Error::make(Errc::wrong_type, "camera: expected an object");
  LibcameraCameraSection out;
  LibcameraStereoConfig& c = out.config;
  StereoTiming& t = c.timing;
  PETRA_TRY(layout_field(doc, obj, t));
  PETRA_TRY(text(doc, obj, "camera", "left", c.left.camera, true));
  PETRA_TRY(
      text(doc, obj, "camera", "right", c.right.camera, t.layout == StereoLayout::two_devices));
  PETRA_TRY(stereo_fields(doc, obj, LibcameraCapture::kMaxBuffers, t, c.left.formats,
                          c.left.buffers, out.triggered));
  for (std::size_t k = 0; k < c.left.formats.size(); ++k)
    if (c.left.formats[k] == PixelFormat::y16)
      return Error::make(Errc::invalid_argument,
                         "camera.formats[%zu]: Y16: libcamera has no 16-bit gray (GREY, YUYV, "
                         "RGB24 or BGR24)",
                         k);
  c.right.formats = c.left.formats;
  c.right.buffers = c.left.buffers;
  return out;
}

Result<GpioSection> parse_gpio(const json::Document& doc, std::uint32_t obj) {
  if (doc.token(obj).type != Type::object)
    return Error::make(Errc::wrong_type, "gpio: expected an object");
  GpioSection out;
  std::array<char, GpioLineConfig::kMaxName> chip{};
  PETRA_TRY(text(doc, obj, "gpio", "chip", chip, false));
  PETRA_TRY(gpio_line(doc, obj, "trigger", chip, out.trigger, out.has_trigger));
  PETRA_TRY(gpio_line(doc, obj, "arm_power", chip, out.arm_power, out.has_arm_power));
  PETRA_TRY(gpio_line(doc, obj, "estop", chip, out.estop, out.has_estop));
  return out;
}

}  // namespace petra::hal
