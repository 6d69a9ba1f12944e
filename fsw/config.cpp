#include "fsw/config.hpp"

#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <memory>
#include <string_view>

#include "algo/core/json_reader.hpp"
#include "hal/file_io.hpp"
#include "hal/udp_can.hpp"

namespace petra::fsw {

namespace {

using json::Document;
using json::Type;

struct Reader {
  const Document& doc;
  const char* base_dir;

  Status number(std::uint32_t obj, const char* section, const char* key, double lo, double hi,
                double& out, bool required = false) const {
    const std::uint32_t t = doc.find(obj, key);
    if (t == 0) {
      if (required) return Error::make(Errc::missing_field, "config: %s.%s: missing", section, key);
      return {};
    }
    if (doc.token(t).type != Type::number)
      return Error::make(Errc::wrong_type, "config: %s.%s: expected a number", section, key);
    const double v = doc.token(t).number;
    if (v < lo || v > hi)
      return Error::make(Errc::out_of_range, "config: %s.%s = %g outside %g..%g", section, key, v,
                         lo, hi);
    out = v;
    return {};
  }

  template <std::size_t N>
  Status text(std::uint32_t obj, const char* section, const char* key, std::array<char, N>& out,
              bool required, bool is_path) const {
    const std::uint32_t t = doc.find(obj, key);
    if (t == 0) {
      if (required) return Error::make(Errc::missing_field, "config: %s.%s: missing", section, key);
      return {};
    }
    if (doc.token(t).type != Type::string)
      return Error::make(Errc::wrong_type, "config: %s.%s: expected a string", section, key);
    const std::string_view s = doc.text_of(t);
    char raw[256];
    if (s.size() >= sizeof(raw) || s.empty())
      return Error::make(Errc::invalid_argument, "config: %s.%s: empty or too long", section, key);
    std::memcpy(raw, s.data(), s.size());
    raw[s.size()] = '\0';
    if (is_path) {
      const Status st = hal::join_path(base_dir, raw, out);
      if (!st)
        return Error::make(Errc::invalid_argument, "config: %s.%s: %s", section, key,
                           st.error().message);
    } else {
      if (s.size() >= N)
        return Error::make(Errc::invalid_argument, "config: %s.%s: too long", section, key);
      std::memcpy(out.data(), raw, s.size() + 1);
    }
    return {};
  }
};

template <class T>
Status get_int(const Reader& r, std::uint32_t obj, const char* section, const char* key, double lo,
               double hi, T& out) {
  double v = static_cast<double>(out);
  PETRA_TRY(r.number(obj, section, key, lo, hi, v));
  if (v != static_cast<double>(static_cast<long long>(v)))
    return Error::make(Errc::invalid_argument, "config: %s.%s: must be a whole number", section,
                       key);
  out = static_cast<T>(v);
  return {};
}

// Every member of object `obj` must be one of `known`: a misspelt key
// ("upink") would otherwise be ignored and its default would fly.
Status only_known_keys(const Document& doc, std::uint32_t obj, const char* section,
                       std::initializer_list<std::string_view> known) {
  std::uint32_t key = obj + 1;
  for (std::uint32_t m = 0; m < doc.token(obj).count; ++m) {
    const std::string_view name = doc.text_of(key);
    bool found = false;
    for (std::string_view k : known) found = found || k == name;
    if (!found) {
      char list[512] = "";
      std::size_t used = 0;
      for (std::string_view k : known) {
        const int n = std::snprintf(list + used, sizeof(list) - used, "%s%.*s", used ? ", " : "",
                                    static_cast<int>(k.size()), k.data());
        if (n < 0 || used + static_cast<std::size_t>(n) >= sizeof(list)) break;
        used += static_cast<std::size_t>(n);
      }
      return Error::make(Errc::invalid_argument,
                         "config: %s%s%.*s: unknown key (expected one of %s)", section,
                         section[0] ? "." : "", static_cast<int>(name.size()), name.data(), list);
    }
    key = doc.token(key + 1).next;
  }
  return {};
}

// The keys of each section (docs/icd.md "petra-fsw configuration", docs/hal.md).
Status check_keys(const Document& doc, std::string_view camera_kind) {
  PETRA_TRY(only_known_keys(
      doc, 0, "",
      {"uplink", "downlink", "loop", "budget", "camera", "gpio", "arm", "calib", "params"}));
  struct Section {
    const char* name;
    std::initializer_list<std::string_view> keys;
  };
  const Section sections[] = {
      {"uplink", {"host", "port", "key_file", "counter_file", "counter_floor"}},
      {"downlink", {"host", "port"}},
      {"loop",
       {"cycle_ms", "commands_per_cycle", "health_period_ms", "watchdog_device", "lock_memory"}},
      {"budget",
       {"image_width", "image_height", "arena_mb", "tlm_queue_packets", "worker_stack_kb",
        "cloud_points", "roi_width", "roi_height"}},
      {"arm", {"can_interface", "mount", "heartbeat_timeout_ms", "sdo_timeout_ms"}},
      {"gpio", {"chip", "trigger", "arm_power", "estop"}},
  };
  for (const Section& s : sections)
    if (const std::uint32_t t = doc.find(0, s.name); t != 0)
      PETRA_TRY(only_known_keys(doc, t, s.name, s.keys));
  if (const std::uint32_t gpio = doc.find(0, "gpio"); gpio != 0) {
    for (const char* line : {"trigger", "arm_power", "estop"}) {
      const std::uint32_t t = doc.find(gpio, line);
      char section[24];
      (void)std::snprintf(section, sizeof(section), "gpio.%s", line);
      if (t != 0 && doc.token(t).type == Type::object)
        PETRA_TRY(only_known_keys(doc, t, section, {"chip", "line", "active_low"}));
    }
  }
  const std::uint32_t camera = doc.find(0, "camera");
  if (camera_kind == "v4l2")
    return only_known_keys(
        doc, camera, "camera",
        {"kind", "layout", "left", "right", "width", "height", "formats", "buffers", "fps",
         "timeout_ms", "max_skew_us", "max_pair_frames", "trigger_width_us", "triggered"});
  if (camera_kind == "libcamera")
    return only_known_keys(
        doc, camera, "camera",
        {"kind", "layout", "left", "right", "width", "height", "formats", "buffers", "timeout_ms",
         "max_skew_us", "max_pair_frames", "trigger_width_us", "triggered"});
  return only_known_keys(doc, camera, "camera", {"kind", "dir"});
}

Status object_or_absent(const Document& doc, std::uint32_t t, const char* name) {
  if (t != 0 && doc.token(t).type != Type::object)
    return Error::make(Errc::wrong_type, "config: %s: expected an object", name);
  return {};
}

// uplink (required) and downlink.
Status parse_links(const Reader& r, std::uint32_t up, std::uint32_t down, FswConfig& c) {
  PETRA_TRY(r.text(up, "uplink", "host", c.cmd_host, false, false));
  PETRA_TRY(get_int(r, up, "uplink", "port", 0, 65535, c.cmd_port));
  PETRA_TRY(r.text(up, "uplink", "key_file", c.key_file, true, true));
  PETRA_TRY(r.text(up, "uplink", "counter_file", c.counter_file, false, true));
  PETRA_TRY(get_int(r, up, "uplink", "counter_floor", 0, 4294967295.0, c.counter_floor));
  if (down != 0) {
    PETRA_TRY(r.text(down, "downlink", "host", c.tlm_host, false, false));
    PETRA_TRY(get_int(r, down, "downlink", "port", 1, 65535, c.tlm_port));
  }
  return {};
}

Status parse_loop(const Reader& r, std::uint32_t loop, FswConfig& c) {
  PETRA_TRY(get_int(r, loop, "loop", "cycle_ms", 1, 1000, c.cycle_ms));
  PETRA_TRY(get_int(r, loop, "loop", "commands_per_cycle", 1, 256, c.commands_per_cycle));
  PETRA_TRY(get_int(r, loop, "loop", "health_period_ms", 10, 60000, c.health_period_ms));
  PETRA_TRY(r.text(loop, "loop", "watchdog_device", c.watchdog_device, false, true));
  const std::uint32_t lock = r.doc.find(loop, "lock_memory");
  if (lock != 0) {
    if (r.doc.token(lock).type != Type::boolean)
      return Error::make(Errc::wrong_type, "config: loop.lock_memory: expected true or false");
    c.lock_memory = r.doc.token(lock).number != 0.0;
  }
  return {};
}

Status parse_budget(const Reader& r, std::uint32_t budget, Budget& b) {
  PETRA_TRY(get_int(r, budget, "budget", "image_width", 16, 8192, b.image_width));
  PETRA_TRY(get_int(r, budget, "budget", "image_height", 16, 8192, b.image_height));
  PETRA_TRY(get_int(r, budget, "budget", "roi_width", 16, 8192, b.roi_width));
  PETRA_TRY(get_int(r, budget, "budget", "roi_height", 16, 8192, b.roi_height));
  if ((b.roi_width == 0) != (b.roi_height == 0))
    return Error::make(Errc::missing_field,
                       "config: budget.roi_width and budget.roi_height go together");
  double arena_mb = 0;
  PETRA_TRY(r.number(budget, "budget", "arena_mb", 1, 4096, arena_mb));
  b.arena_bytes = static_cast<std::size_t>(arena_mb * 1048576.0);
  PETRA_TRY(get_int(r, budget, "budget", "tlm_queue_packets", 32, 65535, b.tlm_queue_packets));
  double stack_kb = static_cast<double>(b.worker_stack_bytes >> 10);
  PETRA_TRY(r.number(budget, "budget", "worker_stack_kb", 64, 65536, stack_kb));
  b.worker_stack_bytes = static_cast<std::size_t>(stack_kb) << 10;
  PETRA_TRY(get_int(r, budget, "budget", "cloud_points", 0, 1000000, b.cloud_points));
  return {};
}

// camera.kind and that kind's section (hal/ parses the hardware ones).
Status parse_camera(const Reader& r, std::uint32_t camera, FswConfig& c) {
  std::array<char, 16> kind{};
  PETRA_TRY(r.text(camera, "camera", "kind", kind, false, false));
  if (kind[0] == '\0' || std::strcmp(kind.data(), "file") == 0) {
    c.camera_kind = CameraKind::file;
    PETRA_TRY(r.text(camera, "camera", "dir", c.camera_dir, true, true));
  } else if (std::strcmp(kind.data(), "v4l2") == 0) {
    c.camera_kind = CameraKind::v4l2;
    auto v4l2 = hal::parse_v4l2_camera(r.doc, camera);
    if (!v4l2) return Error::make(v4l2.code(), "config: %s", v4l2.error().message);
    c.v4l2 = *v4l2;
  } else if (std::strcmp(kind.data(), "libcamera") == 0) {
    c.camera_kind = CameraKind::libcamera;
    auto lc = hal::parse_libcamera_camera(r.doc, camera);
    if (!lc) return Error::make(lc.code(), "config: %s", lc.error().message);
    c.libcamera = *lc;
  } else {
    return Error::make(Errc::invalid_argument,
                       "config: camera.kind '%s': expected file, v4l2 or libcamera", kind.data());
  }
  return {};
}

// gpio lines; a triggered camera needs the trigger line.
Status parse_gpio_lines(const Document& doc, FswConfig& c) {
  const std::uint32_t gpio = doc.find(0, "gpio");
  if (gpio != 0) {
    auto lines = hal::parse_gpio(doc, gpio);
    if (!lines) return Error::make(lines.code(), "config: %s", lines.error().message);
    c.gpio = *lines;
  }
  const bool triggered = (c.camera_kind == CameraKind::v4l2 && c.v4l2.triggered) ||
                         (c.camera_kind == CameraKind::libcamera && c.libcamera.triggered);
  if (triggered && !c.gpio.has_trigger)
    return Error::make(Errc::missing_field,
                       "config: camera.triggered needs gpio.trigger (the trigger line)");
  return {};
}

Status parse_arm_mount(const Document& doc, std::uint32_t mount, FswConfig& c) {
  if (doc.token(mount).type != Type::array || doc.token(mount).count != 4)
    return Error::make(Errc::wrong_type, "config: arm.mount: expected [x_mm, y_mm, z_mm, yaw_deg]");
  for (std::uint32_t k = 0; k < 4; ++k) {
    const json::Token& t = doc.token(doc.element(mount, k));
    if (t.type != Type::number || !(t.number >= -1e5 && t.number <= 1e5))
      return Error::make(Errc::out_of_range, "config: arm.mount[%u]: expected a number within 1e5",
                         k);
    c.arm.mount[k] = t.number;
  }
  c.arm.has_mount = true;
  return {};
}

// arm (absent: no arm): its CAN link, mount and heartbeat.
Status parse_arm(const Reader& r, FswConfig& c) {
  const Document& doc = r.doc;
  const std::uint32_t arm = doc.find(0, "arm");
  PETRA_TRY(object_or_absent(doc, arm, "arm"));
  if (arm == 0) return {};
  c.arm.enabled = true;
  PETRA_TRY(r.text(arm, "arm", "can_interface", c.arm.can_interface, true, false));
  if (hal::is_udp_can_spec(c.arm.can_interface.data())) {
    if (auto spec = hal::parse_udp_can_spec(c.arm.can_interface.data()); !spec)
      return Error::make(Errc::invalid_argument, "config: arm.can_interface %s",
                         spec.error().message);
  }
  const std::uint32_t mount = doc.find(arm, "mount");
  if (mount != 0) PETRA_TRY(parse_arm_mount(doc, mount, c));
  PETRA_TRY(get_int(r, arm, "arm", "heartbeat_timeout_ms", 200, 60000, c.arm.heartbeat_timeout_ms));
  PETRA_TRY(get_int(r, arm, "arm", "sdo_timeout_ms", 50, 10000, c.arm.sdo_timeout_ms));
  return {};
}

}  // namespace

Result<FswConfig> parse_config(const char* text, std::size_t size, const char* base_dir) {
  auto tokens = std::make_unique<json::Token[]>(4096);  // init only
  auto doc =
      Document::parse(std::string_view(text, size), std::span<json::Token>(tokens.get(), 4096));
  if (!doc) return Error::make(Errc::parse_error, "config: %s", doc.error().message);
  if (doc->token(0).type != Type::object)
    return Error::make(Errc::wrong_type, "config: top level must be an object");
  FswConfig c;
  (void)std::snprintf(c.cmd_host.data(), c.cmd_host.size(), "127.0.0.1");
  (void)std::snprintf(c.tlm_host.data(), c.tlm_host.size(), "127.0.0.1");
  const Reader r{*doc, base_dir};

  const std::uint32_t up = doc->find(0, "uplink");
  const std::uint32_t down = doc->find(0, "downlink");
  const std::uint32_t loop = doc->find(0, "loop");
  const std::uint32_t budget = doc->find(0, "budget");
  const std::uint32_t camera = doc->find(0, "camera");
  PETRA_TRY(object_or_absent(*doc, up, "uplink"));
  PETRA_TRY(object_or_absent(*doc, down, "downlink"));
  PETRA_TRY(object_or_absent(*doc, loop, "loop"));
  PETRA_TRY(object_or_absent(*doc, budget, "budget"));
  PETRA_TRY(object_or_absent(*doc, camera, "camera"));
  if (up == 0) return Error::make(Errc::missing_field, "config: uplink: missing");
  if (camera == 0) return Error::make(Errc::missing_field, "config: camera: missing");
  PETRA_TRY(object_or_absent(*doc, doc->find(0, "gpio"), "gpio"));
  PETRA_TRY(object_or_absent(*doc, doc->find(0, "arm"), "arm"));
  const std::uint32_t camera_kind = doc->find(camera, "kind");
  PETRA_TRY(check_keys(*doc, camera_kind != 0 ? doc->text_of(camera_kind) : std::string_view()));

  PETRA_TRY(parse_links(r, up, down, c));
  if (loop != 0) PETRA_TRY(parse_loop(r, loop, c));
  if (budget != 0) PETRA_TRY(parse_budget(r, budget, c.budget));
  PETRA_TRY(parse_camera(r, camera, c));
  PETRA_TRY(parse_gpio_lines(*doc, c));
  PETRA_TRY(parse_arm(r, c));
  PETRA_TRY(r.text(0, "", "calib", c.calib_file, false, true));
  PETRA_TRY(r.text(0, "", "params", c.param_file, false, true));
  return c;
}

Result<FswConfig> load_config(const char* path) {
  auto buf = std::make_unique<char[]>(65536);  // init only
  auto n = hal::read_small_file(path, std::span<char>(buf.get(), 65536));
  if (!n) return n.error();
  // Relative paths in the file are resolved against its folder: a cut path
  // would resolve them somewhere else.
  char dir[256];
  if (std::snprintf(dir, sizeof(dir), "%s", path) >= static_cast<int>(sizeof(dir)))
    return Error::make(Errc::invalid_argument, "config path: longer than %zu characters",
                       sizeof(dir) - 1);
  char* slash = std::strrchr(dir, '/');
  if (slash != nullptr)
    *slash = '\0';
  else
    (void)std::snprintf(dir, sizeof(dir), ".");
  return parse_config(buf.get(), *n, dir);
}

}  // namespace petra::fsw
