// petra-fsw --config FILE [--counter-floor N]: the onboard service. Loads the configuration,
// opens the devices (camera, GPIO lines, the arm's CAN bus), allocates every
// buffer, then runs the executive's loop until SIGINT or SIGTERM. Exit status 0 after a clean stop;
// 1 with a one-line reason on stderr when initialisation fails.
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "fsw/arm/flight_arm.hpp"
#include "fsw/executive.hpp"
#include "fsw/flight_devices.hpp"
#include "fsw/pipeline_factory.hpp"
#include "hal/clock.hpp"
#include "hal/socketcan.hpp"
#include "hal/udp_can.hpp"

namespace {

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) {
  g_stop = 1;
}

int usage() {
  (void)std::fprintf(
      stderr,
      "usage: petra-fsw --config FILE [--counter-floor N]\n"
      "  --counter-floor N  commands need a counter above N; the way past a missing\n"
      "                     or corrupt counter file (docs/ops.md \"Command counter\")\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  const char* config_path = nullptr;
  long long floor = -1;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--config") == 0 && i + 1 < argc) {
      config_path = argv[++i];
    } else if (std::strcmp(argv[i], "--counter-floor") == 0 && i + 1 < argc) {
      char* end = nullptr;
      floor = std::strtoll(argv[++i], &end, 10);
      if (*end != '\0' || floor < 0 || floor > 4294967295LL) {
        (void)std::fprintf(stderr, "petra-fsw: --counter-floor: expected 0..4294967295\n");
        return usage();
      }
    } else if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
      return usage();
    } else {
      (void)std::fprintf(stderr, "petra-fsw: unknown argument '%s'\n", argv[i]);
      return usage();
    }
  }
  if (config_path == nullptr) return usage();

  auto config = petra::fsw::load_config(config_path);
  if (!config) {
    (void)std::fprintf(stderr, "petra-fsw: %s\n", config.error().message);
    return 1;
  }
  if (floor >= 0) config->counter_floor = floor;
  static petra::hal::SystemClock clock;
  static petra::fsw::FlightDevices devices;
  if (auto s = devices.open(*config); !s) {
    (void)std::fprintf(stderr, "petra-fsw: %s\n", s.error().message);
    return 1;
  }
  petra::fsw::Dependencies deps;
  deps.camera = &devices.camera();
  deps.clock = &clock;
  deps.estop = devices.estop();  // asserted: arm quick stop and SAFE
  deps.job = petra::fsw::flight_pipeline();
  static petra::hal::SocketCanPort socketcan;
  static petra::hal::UdpCanPort udp_can;
  static petra::fsw::arm::FlightArm arm;
  if (config->arm.enabled) {
    // The arm's drives (docs/arm.md): boot starts here, ARM_READY follows.
    // "udp:L:P" reaches simulated drives in another process (`petra sim-arm
    // --udp`) where the kernel has no CAN; any other name is SocketCAN.
    const char* iface = config->arm.can_interface.data();
    petra::hal::CanPort* can = &socketcan;
    petra::Status opened;
    if (petra::hal::is_udp_can_spec(iface)) {
      auto spec = petra::hal::parse_udp_can_spec(iface);
      opened = spec ? udp_can.open(*spec) : petra::Status(spec.error());
      can = &udp_can;
    } else {
      opened = socketcan.open(iface);
    }
    if (!opened) {
      (void)std::fprintf(stderr, "petra-fsw: arm: %s\n", opened.error().message);
      return 1;
    }
    // Drives powered before the master boots them (a boot-up message starts configuration).
    if (auto s = devices.power_arm(true); !s) {
      (void)std::fprintf(stderr, "petra-fsw: arm: %s\n", s.error().message);
      return 1;
    }
    petra::fsw::arm::ArmServiceConfig arm_config;
    if (config->arm.has_mount) {
      const auto& m = config->arm.mount;
      arm_config.geometry.world_from_base =
          Eigen::Translation3d(m[0], m[1], m[2]) *
          Eigen::AngleAxisd(m[3] * 3.14159265358979323846 / 180.0, Eigen::Vector3d::UnitZ());
    }
    if (auto s = arm.init(arm_config, *can, clock); !s) {
      (void)std::fprintf(stderr, "petra-fsw: arm: %s\n", s.error().message);
      return 1;
    }
    deps.arm = &arm;
  }
  static petra::fsw::Executive exec;
  if (auto s = exec.init(*config, deps); !s) {
    (void)std::fprintf(stderr, "petra-fsw: %s\n", s.error().message);
    return 1;
  }
  if (std::signal(SIGINT, on_signal) == SIG_ERR || std::signal(SIGTERM, on_signal) == SIG_ERR)
    (void)std::fprintf(stderr, "petra-fsw: cannot handle SIGINT/SIGTERM; no orderly stop\n");
  (void)std::fprintf(
      stderr,
      "petra-fsw: running: commands on udp %s:%u, telemetry to %s:%u, camera %s, "
      "pipeline %s, arm %s, e-stop %s, %zu bytes allocated at init\n",
      config->cmd_host.data(), exec.command_port(), config->tlm_host.data(), config->tlm_port,
      devices.camera_description(), deps.job != nullptr ? deps.job->name() : "none",
      config->arm.enabled ? config->arm.can_interface.data() : "none",
      deps.estop != nullptr ? config->gpio.estop.line.data() : "none", exec.memory_bytes());
  exec.run(&g_stop);
  exec.shutdown();
  devices.close();  // arm power off
  (void)std::fprintf(stderr, "petra-fsw: stopped after %u cycles\n", exec.loop_counters().cycles);
  return 0;
}
