// petra-fsw --config FILE [--counter-floor N]: the onboard service (--memory-table: the
// generated table of docs/memory.md). Loads the configuration,
// opens the devices (camera, GPIO lines, the arm's CAN bus), allocates every
// buffer, then runs the executive's loop until SIGINT or SIGTERM. Exit status 0 after a clean stop
// and for --help and --version; 1 with a one-line reason on stderr when initialisation fails;
// 2 for a usage error ("petra-fsw: ..." and the usage line on stderr).
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "fsw/arm/flight_arm.hpp"
#include "fsw/arm_geometry.hpp"
#include "fsw/executive.hpp"
#include "fsw/flight_devices.hpp"
#include "fsw/memory_table.hpp"
#include "fsw/pipeline_factory.hpp"
#include "hal/clock.hpp"
#include "hal/socketcan.hpp"
#include "hal/udp_can.hpp"

namespace {

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) {
  g_stop = 1;
}

#ifndef PETRA_VERSION
#define PETRA_VERSION "unknown"
#endif

constexpr const char* kUsage =
    "usage: petra-fsw --config FILE [--counter-floor N] | --memory-table | --help | --version\n";

// The generated table of docs/memory.md.
int print_memory_table() {
  static char table[8192];
  (void)petra::fsw::format_memory_doc_table(table, sizeof(table));
  (void)std::fputs(table, stdout);
  return 0;
}

int usage_error(const char* why, const char* arg) {
  (void)std::fprintf(stderr, "petra-fsw: %s%s%s%s\n%s", why, arg[0] ? " '" : "", arg,
                     arg[0] ? "'" : "", kUsage);
  return 2;
}

int help() {
  (void)std::printf(
      "%s\nThe onboard service: loads the configuration (JSON, docs/icd.md \"petra-fsw "
      "configuration\"),\nopens the devices, allocates every buffer, then serves commands and "
      "sends telemetry\nuntil SIGINT or SIGTERM.\n  --config FILE   the configuration\n"
      "  --counter-floor N  commands need a counter above N: the way past a missing or\n"
      "                  corrupt counter file (docs/ops.md \"Command counter\")\n"
      "  --memory-table  the per-stage memory table (docs/memory.md)\n"
      "  --help          this text\n  --version       the version\n",
      kUsage);
  return 0;
}

struct Args {
  const char* config_path = nullptr;
  long long floor = -1;  // --counter-floor, -1 when not given
};

// Returns -1 to go on, else the exit status (--help, --version, usage error).
int parse_args(int argc, char** argv, Args& args) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--config") == 0 && i + 1 < argc) {
      args.config_path = argv[++i];
    } else if (std::strcmp(argv[i], "--config") == 0) {
      return usage_error("--config needs a file name", "");
    } else if (std::strcmp(argv[i], "--counter-floor") == 0 && i + 1 < argc) {
      char* end = nullptr;
      args.floor = std::strtoll(argv[++i], &end, 10);
      if (*end != '\0' || args.floor < 0 || args.floor > 4294967295LL)
        return usage_error("--counter-floor: expected 0..4294967295, got", argv[i]);
    } else if (std::strcmp(argv[i], "--memory-table") == 0) {
      return print_memory_table();
    } else if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
      return help();
    } else if (std::strcmp(argv[i], "--version") == 0) {
      (void)std::printf("petra-fsw %s\n", PETRA_VERSION);
      return 0;
    } else {
      return usage_error("unknown argument", argv[i]);
    }
  }
  if (args.config_path == nullptr) return usage_error("--config FILE is required", "");
  return -1;
}

// The arm's drives (docs/arm.md): boot starts here, ARM_READY follows.
// "udp:L:P" reaches simulated drives in another process (`petra sim-arm
// --udp`) where the kernel has no CAN; any other name is SocketCAN. Returns
// false after printing the reason.
bool start_arm(const petra::fsw::FswConfig& config, petra::fsw::FlightDevices& devices,
               petra::hal::SystemClock& clock, petra::hal::SocketCanPort& socketcan,
               petra::hal::UdpCanPort& udp_can, petra::fsw::arm::FlightArm& arm) {
  const char* iface = config.arm.can_interface.data();
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
    return false;
  }
  // Drives powered before the master boots them (a boot-up message starts configuration).
  if (auto s = devices.power_arm(true); !s) {
    (void)std::fprintf(stderr, "petra-fsw: arm: %s\n", s.error().message);
    return false;
  }
  petra::fsw::arm::ArmServiceConfig arm_config;
  arm_config.heartbeat_timeout_ms = config.arm.heartbeat_timeout_ms;
  if (config.arm.sdo_timeout_ms != 0) arm_config.timing.sdo_timeout_ms = config.arm.sdo_timeout_ms;
  arm_config.geometry = petra::fsw::arm_geometry(config);
  if (auto s = arm.init(arm_config, *can, clock); !s) {
    (void)std::fprintf(stderr, "petra-fsw: arm: %s\n", s.error().message);
    return false;
  }
  return true;
}

// The one-line summary of what runs, and the pipeline's memory per stage.
void report_running(const petra::fsw::FswConfig& config, const petra::fsw::Executive& exec,
                    const petra::fsw::FlightDevices& devices,
                    const petra::fsw::Dependencies& deps) {
  (void)std::fprintf(
      stderr,
      "petra-fsw: running: commands on udp %s:%u, telemetry to %s:%u, camera %s, "
      "pipeline %s, arm %s, e-stop %s, %zu bytes allocated at init\n",
      config.cmd_host.data(), exec.command_port(), config.tlm_host.data(), config.tlm_port,
      devices.camera_description(), deps.job != nullptr ? deps.job->name() : "none",
      config.arm.enabled ? config.arm.can_interface.data() : "none",
      deps.estop != nullptr ? config.gpio.estop.line.data() : "none", exec.memory_bytes());
  if (deps.job != nullptr) {
    static char table[2048];  // the arena's share per stage (MiB), docs/memory.md
    (void)deps.job->describe_memory(table, sizeof(table));
    (void)std::fprintf(stderr, "petra-fsw: pipeline memory (MiB):\n%s", table);
  }
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  if (const int status = parse_args(argc, argv, args); status >= 0) return status;

  auto config = petra::fsw::load_config(args.config_path);
  if (!config) {
    (void)std::fprintf(stderr, "petra-fsw: %s\n", config.error().message);
    return 1;
  }
  if (args.floor >= 0) config->counter_floor = args.floor;
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
  deps.job = petra::fsw::flight_pipeline(clock);
  static petra::hal::SocketCanPort socketcan;
  static petra::hal::UdpCanPort udp_can;
  static petra::fsw::arm::FlightArm arm;
  if (config->arm.enabled) {
    if (!start_arm(*config, devices, clock, socketcan, udp_can, arm)) return 1;
    deps.arm = &arm;
  }
  static petra::fsw::Executive exec;
  if (auto s = exec.init(*config, deps); !s) {
    (void)std::fprintf(stderr, "petra-fsw: %s\n", s.error().message);
    return 1;
  }
  if (std::signal(SIGINT, on_signal) == SIG_ERR || std::signal(SIGTERM, on_signal) == SIG_ERR)
    (void)std::fprintf(stderr, "petra-fsw: cannot handle SIGINT/SIGTERM; no orderly stop\n");
  report_running(*config, exec, devices, deps);
  exec.run(&g_stop);
  exec.shutdown();
  devices.close();  // arm power off
  (void)std::fprintf(stderr, "petra-fsw: stopped after %u cycles\n", exec.loop_counters().cycles);
  return 0;
}
