// The executive's configuration (`petra-fsw --config FILE`, JSON, format in
// docs/icd.md "petra-fsw configuration"): links, files, loop rates and the
// memory budget every buffer is sized from at init. Relative paths are taken
// relative to the configuration file's folder.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "algo/core/result.hpp"
#include "hal/device_config.hpp"

namespace petra::fsw {

using Path = std::array<char, 256>;
using Host = std::array<char, 64>;

struct Budget {
  int image_width = 1024;  // largest frame the camera may deliver
  int image_height = 768;
  // Largest ROI SELECT_ROI may ask (original px); 0: the pipeline's default
  // (512 x 384), or the largest that fits arena_bytes when that is given.
  int roi_width = 0;
  int roi_height = 0;
  std::size_t arena_bytes = 0;          // pipeline arena; 0: what the ROI budget needs
  std::size_t tlm_queue_packets = 256;  // downlink queue slots
  std::size_t worker_stack_bytes = 1u << 20;
  std::size_t cloud_points = 8192;  // point cloud product capacity
};

// The arm (optional section "arm"): its drives' CAN interface and where it
// sits in the world (docs/arm.md). Absent: no arm, arm commands fail.
struct ArmConfig {
  bool enabled = false;
  // SocketCAN interface ("can0", "vcan0"), or "udp:LOCAL_PORT:PEER_PORT" for
  // simulated drives in another process (hal/udp_can.hpp).
  std::array<char, 16> can_interface{};
  bool has_mount = false;
  std::array<double, 4> mount{};  // base x, y, z (mm, world) and yaw (deg about world z)
  // "heartbeat_timeout_ms" (optional, 200..60000): heartbeat consumer time both
  // ways; absent (0) keeps the flight defaults (fsw/arm/arm_service.hpp).
  std::uint16_t heartbeat_timeout_ms = 0;
  // "sdo_timeout_ms" (optional, 50..10000): the master's wait for each
  // configuration answer; absent (0) keeps the flight default (200 ms).
  std::uint16_t sdo_timeout_ms = 0;
};

// Where stereo pairs come from ("camera.kind"): a folder of PGM pairs, V4L2
// cameras, or cameras through libcamera.
enum class CameraKind : std::uint8_t { file, v4l2, libcamera };

struct FswConfig {
  Host cmd_host{};  // command port: bind address and port
  std::uint16_t cmd_port = 47100;
  Host tlm_host{};  // telemetry destination
  std::uint16_t tlm_port = 47101;
  Path key_file{};  // uplink HMAC key (64 hex digits); required
  // Last accepted command counter, kept across reboots and power cuts; always
  // kept: empty means beside the key, KEY_FILE.fsw-counter (docs/ops.md).
  Path counter_file{};
  // The operator's way past a missing or corrupt counter file (petra-fsw
  // --counter-floor N, or uplink.counter_floor): commands need a counter above
  // N. -1: none given, and such a file stops the start.
  std::int64_t counter_floor = -1;
  Path param_file{};  // parameter defaults; optional
  Path calib_file{};  // calib.json for the pipeline; optional
  CameraKind camera_kind = CameraKind::file;
  Path camera_dir{};                      // kind "file": the folder of pairs
  hal::V4l2CameraSection v4l2;            // kind "v4l2" (docs/hal.md "Device configuration")
  hal::LibcameraCameraSection libcamera;  // kind "libcamera" (the same fields but fps)
  hal::GpioSection gpio;        // section "gpio": e-stop, arm power, trigger; absent = none wired
  Path watchdog_device{};       // e.g. /dev/watchdog; optional (none on development hosts)
  std::uint32_t cycle_ms = 10;  // minor frame
  std::uint32_t commands_per_cycle = 32;  // uplink datagrams drained per cycle at most
  std::uint32_t health_period_ms = 500;
  bool lock_memory = false;  // mlockall after init (needs CAP_IPC_LOCK)
  Budget budget;
  ArmConfig arm;
};

// Parses the JSON text; `base_dir` resolves relative paths. Errors name the field.
Result<FswConfig> parse_config(const char* text, std::size_t size, const char* base_dir);
// Reads and parses a configuration file.
Result<FswConfig> load_config(const char* path);

}  // namespace petra::fsw
