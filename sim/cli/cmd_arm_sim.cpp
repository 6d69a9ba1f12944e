// `petra sim-arm`: the arm's five simulated CANopen drives.
//   --can IFACE   the drives on a SocketCAN interface (vcan0 in the HIL bench),
//                 in real time, for the flight master to talk to; runs until
//                 --duration ends or Ctrl-C. IFACE "udp:LOCAL:PEER": CAN over
//                 UDP on 127.0.0.1 (hal/udp_can.hpp), for a petra-fsw
//                 configured with arm.can_interface "udp:PEER:LOCAL" on a
//                 host without AF_CAN.
//   --loopback    drives and the flight CANopen master in one process on the
//                 loopback bus, in simulated time: boot, enable, move to
//                 --target, quick stop; prints the exchange; exit 1 on a fault.
// Faults (repeatable): --fault NODE:KIND@SECONDS, KIND one of heartbeat,
// power-off, stall, refuse-enable, emcy=0xCODE.
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "algo/arm/kinematics.hpp"
#include "hal/can_loopback.hpp"
#include "hal/canopen/canopen_master.hpp"
#include "hal/socketcan.hpp"
#include "hal/udp_can.hpp"
#include "sim/arm/sim_arm_bus.hpp"
#include "sim/arm/sim_arm_setup.hpp"
#include "sim/cli/commands.hpp"

namespace petra::cli {

namespace {

std::atomic<bool> g_arm_sim_stop{false};

struct FaultPlan {
  std::size_t drive = 0;  // index
  std::string kind;
  std::uint16_t emcy = 0;
  std::int64_t at_ms = 0;
  bool done = false;
};

// "3:stall@1.5" -> drive index 2, kind stall, at 1500 ms.
bool parse_fault(const std::string& text, FaultPlan& f, std::string& why) {
  const auto colon = text.find(':');
  const auto at = text.find('@');
  if (colon == std::string::npos || at == std::string::npos || at < colon) {
    why = "--fault '" + text + "': expected NODE:KIND@SECONDS";
    return false;
  }
  const int node = std::atoi(text.substr(0, colon).c_str());
  if (node < 1 || node > static_cast<int>(canopen::kArmJoints)) {
    why = "--fault '" + text + "': node must be 1..5";
    return false;
  }
  f.drive = static_cast<std::size_t>(node - 1);
  f.kind = text.substr(colon + 1, at - colon - 1);
  const double s = std::atof(text.substr(at + 1).c_str());
  if (!(s >= 0.0) || s > 3600.0) {
    why = "--fault '" + text + "': time must be 0..3600 s";
    return false;
  }
  f.at_ms = static_cast<std::int64_t>(s * 1000.0);
  if (f.kind.rfind("emcy=", 0) == 0) {
    const unsigned long code = std::strtoul(f.kind.c_str() + 5, nullptr, 0);
    if (code == 0 || code > 0xFFFF) {
      why = "--fault '" + text + "': emcy code must be 0x0001..0xFFFF";
      return false;
    }
    f.emcy = static_cast<std::uint16_t>(code);
    f.kind = "emcy";
  }
  if (f.kind != "heartbeat" && f.kind != "power-off" && f.kind != "stall" &&
      f.kind != "refuse-enable" && f.kind != "emcy") {
    why = "--fault '" + text +
          "': kind must be heartbeat, power-off, stall, refuse-enable or emcy=0xCODE";
    return false;
  }
  return true;
}

bool parse_pose(const std::string& text, const char* name, std::array<double, 5>& rad,
                std::string& why) {
  std::stringstream ss(text);
  std::string item;
  std::size_t n = 0;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (n == 5 || end == item.c_str() || *end != '\0' || !std::isfinite(v)) {
      why = std::string(name) + " '" + text + "': expected 5 angles in degrees, comma separated";
      return false;
    }
    rad[n++] = v * arm::kRadPerDeg;
  }
  if (n != 5) {
    why = std::string(name) + " '" + text + "': expected 5 angles in degrees";
    return false;
  }
  return true;
}

void apply_due_faults(std::vector<FaultPlan>& faults, sim::SimArmBus& drives, std::int64_t now_ms) {
  for (FaultPlan& f : faults) {
    if (f.done || now_ms < f.at_ms) continue;
    f.done = true;
    sim::SimDrive& d = drives.drive(f.drive);
    if (f.kind == "heartbeat") d.stop_heartbeat(true);
    if (f.kind == "power-off") d.power_off();
    if (f.kind == "stall") d.stall(true);
    if (f.kind == "refuse-enable") d.refuse_enable(true);
    if (f.kind == "emcy") drives.inject_fault(f.drive, f.emcy);
    std::printf("%8.3f s  inject  node %zu %s\n", static_cast<double>(now_ms) * 1e-3, f.drive + 1,
                f.kind.c_str());
  }
}

void print_event(const canopen::MasterEvent& e, std::int64_t now_ms) {
  std::printf("%8.3f s  master  node %u %-13s", static_cast<double>(now_ms) * 1e-3, e.node,
              canopen::link_event_name(e.event));
  if (e.event == canopen::LinkEvent::fault) {
    std::printf(" %s (0x%06X)",
                canopen::drive_fault_name(static_cast<canopen::DriveFault>(e.detail >> 24)),
                e.detail & 0xFFFFFF);
  } else if (e.event == canopen::LinkEvent::emergency || e.event == canopen::LinkEvent::bad_frame) {
    std::printf(" 0x%04X", e.detail);
  } else if (e.event == canopen::LinkEvent::bus_state) {
    std::printf(" %s", hal::can_bus_state_name(static_cast<hal::CanBusState>(e.detail)));
  }
  std::printf("\n");
}

int run_loopback(const std::array<double, 5>& initial, const std::array<double, 5>& target,
                 std::vector<FaultPlan>& faults) {
  const sim::ArmDriveConfigs configs = sim::default_arm_drive_configs();
  auto bus = std::make_unique<hal::CanLoopbackBus>();
  auto master_port = bus->attach();
  auto drive_port = bus->attach();
  if (!master_port || !drive_port) return fail("sim-arm", "loopback: cannot attach");
  auto master = std::make_unique<canopen::CanopenMaster>();
  if (auto s = master->configure(configs, canopen::LinkTiming{}, **master_port); !s) {
    return fail("sim-arm", s.error().message);
  }
  auto drives = std::make_unique<sim::SimArmBus>();
  const sim::ArmSimParams params = sim::sim_params_at(configs, initial);
  if (auto s = drives->configure(params, **drive_port); !s)
    return fail("sim-arm", s.error().message);
  drives->power_on(0);
  master->boot(0);
  enum class Phase { booting, enabling, moving, stopping, done } phase = Phase::booting;
  std::int64_t now = 0;
  bool faulted = false;
  bool reached = false;
  const std::int64_t limit_ms = 60000;
  while (phase != Phase::done && now < limit_ms) {
    now += 10;
    apply_due_faults(faults, *drives, now);
    master->step(now);
    drives->step(now);
    canopen::MasterEvent e;
    while (master->pop_event(e)) print_event(e, now);
    if (master->any_fault()) faulted = true;
    switch (phase) {
      case Phase::booting:
        if (master->all_in(canopen::LinkState::operational)) {
          master->enable(now);
          phase = Phase::enabling;
        }
        break;
      case Phase::enabling:
        if (master->all_in(canopen::LinkState::ready)) {
          if (auto s = master->set_targets(target); !s) return fail("sim-arm", s.error().message);
          std::printf("%8.3f s  master  targets sent\n", static_cast<double>(now) * 1e-3);
          phase = Phase::moving;
        }
        break;
      case Phase::moving:
        if (master->all_targets_reached()) {
          reached = true;
          std::printf("%8.3f s  master  all targets reached\n", static_cast<double>(now) * 1e-3);
          master->quick_stop();
          phase = Phase::stopping;
        }
        break;
      case Phase::stopping:
        if (master->all_in(canopen::LinkState::quick_stopped)) phase = Phase::done;
        break;
      case Phase::done:
        break;
    }
    if (faulted && phase != Phase::done) {
      // Let the quick stops go out, then report.
      for (int k = 0; k < 20; ++k) {
        now += 10;
        master->step(now);
        drives->step(now);
        while (master->pop_event(e)) print_event(e, now);
      }
      phase = Phase::done;
    }
  }
  std::printf("joint  target_deg  drive_deg  master_state\n");
  for (std::size_t j = 0; j < 5; ++j) {
    const double drive_rad = canopen::counts_to_position(
        configs[j], static_cast<std::int32_t>(std::lround(drives->drive(j).position_counts())));
    std::printf("th%zu  %10.3f  %9.3f  %s\n", j + 1, target[j] / arm::kRadPerDeg,
                drive_rad / arm::kRadPerDeg, canopen::link_state_name(master->drive(j).state()));
  }
  const auto& c = master->counters();
  std::printf("frames: sent %u, received %u, bad %u, foreign %u, send errors %u\n", c.frames_sent,
              c.frames_received, c.bad_frames, c.foreign_frames, c.send_errors);
  if (faulted) return fail("sim-arm", "a drive fault stopped the arm (see the events above)");
  if (!reached) return fail("sim-arm", "targets not reached within 60 s of simulated time");
  return 0;
}

int run_socketcan(const std::string& iface, const std::array<double, 5>& initial, double duration_s,
                  std::vector<FaultPlan>& faults) {
  std::unique_ptr<hal::CanPort> port;
  if (hal::is_udp_can_spec(iface.c_str())) {
    auto spec = hal::parse_udp_can_spec(iface.c_str());
    if (!spec) return fail("sim-arm", ("--can " + std::string(spec.error().message)).c_str());
    auto udp = std::make_unique<hal::UdpCanPort>();
    if (auto s = udp->open(*spec); !s) return fail("sim-arm", s.error().message);
    port = std::move(udp);
  } else {
    if (!hal::socketcan_available())
      return fail("sim-arm",
                  "AF_CAN not available on this kernel (use --loopback or --can udp:L:P)");
    auto can = std::make_unique<hal::SocketCanPort>();
    if (auto s = can->open(iface.c_str()); !s) return fail("sim-arm", s.error().message);
    port = std::move(can);
  }
  const sim::ArmDriveConfigs configs = sim::default_arm_drive_configs();
  auto drives = std::make_unique<sim::SimArmBus>();
  if (auto s = drives->configure(sim::sim_params_at(configs, initial), *port); !s) {
    return fail("sim-arm", s.error().message);
  }
  std::signal(SIGINT, [](int) { g_arm_sim_stop = true; });
  std::signal(SIGTERM, [](int) { g_arm_sim_stop = true; });
  const auto start = std::chrono::steady_clock::now();
  auto now_ms = [&] {
    return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() -
                                                                 start)
        .count();
  };
  drives->power_on(0);
  std::printf("sim-arm: 5 drives (nodes 1-5) on %s\n", iface.c_str());
  std::fflush(stdout);
  std::array<canopen::DriveState, 5> shown{};
  shown.fill(canopen::DriveState::unknown);
  while (!g_arm_sim_stop &&
         (duration_s <= 0.0 || static_cast<double>(now_ms()) < duration_s * 1000.0)) {
    const std::int64_t t = now_ms();
    apply_due_faults(faults, *drives, t);
    drives->step(t);
    for (std::size_t j = 0; j < 5; ++j) {
      const canopen::DriveState s = drives->drive(j).drive_state();
      if (s != shown[j]) {
        std::printf("%8.3f s  node %zu  %s\n", static_cast<double>(t) * 1e-3, j + 1,
                    canopen::drive_state_name(s));
        std::fflush(stdout);
        shown[j] = s;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  const auto h = port->health();
  std::printf(
      "sim-arm: stopped; frames sent %u, received %u, bus %s, error frames %u, send errors %u\n",
      h.frames_sent, h.frames_received, hal::can_bus_state_name(h.state), h.error_frames,
      drives->send_errors());
  return 0;
}

}  // namespace

void add_arm_sim(CLI::App& app, Outcome& outcome, const char* name) {
  auto* cmd =
      app.add_subcommand(name, "Simulated CANopen drives of the arm (SocketCAN or loopback)");
  static std::string iface;
  static bool loopback = false;
  static std::string initial_text = "0,0,145,35,0";
  static std::string target_text = "40,50,70,130,-20";
  static double duration_s = 0.0;
  static std::vector<std::string> fault_texts;
  auto* can_opt = cmd->add_option(
      "--can", iface, "SocketCAN interface for the drives (e.g. vcan0), or udp:LOCAL:PEER ports");
  cmd->add_flag("--loopback", loopback,
                "drives and the flight master in one process, simulated time")
      ->excludes(can_opt);
  cmd->add_option("--initial", initial_text,
                  "initial joint angles, deg (default: stow 0,0,145,35,0)");
  cmd->add_option("--target", target_text, "loopback: joint angles to move to, deg");
  cmd->add_option("--duration", duration_s, "--can: seconds to run (default: until Ctrl-C)");
  cmd->add_option("--fault", fault_texts,
                  "NODE:KIND@SECONDS (heartbeat|power-off|stall|refuse-enable|emcy=0xCODE)");
  cmd->callback([&outcome] {
    std::string why;
    std::array<double, 5> initial{}, target{};
    if (!parse_pose(initial_text, "--initial", initial, why) ||
        !parse_pose(target_text, "--target", target, why)) {
      outcome.exit_code = fail("sim-arm", why.c_str());
      return;
    }
    std::vector<FaultPlan> faults;
    for (const std::string& t : fault_texts) {
      FaultPlan f;
      if (!parse_fault(t, f, why)) {
        outcome.exit_code = fail("sim-arm", why.c_str());
        return;
      }
      faults.push_back(f);
    }
    if (loopback) {
      outcome.exit_code = run_loopback(initial, target, faults);
    } else if (!iface.empty()) {
      outcome.exit_code = run_socketcan(iface, initial, duration_s, faults);
    } else {
      outcome.exit_code = fail("sim-arm", "give --can IFACE or --loopback");
    }
  });
}

}  // namespace petra::cli
