// The CANopen master against the simulated drives over the loopback bus: the
// whole exchange (boot, configuration, enable, motion, quick stop) and every
// injected fault seen by the master as the right fault and event.
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <numbers>
#include <vector>

#include "algo/arm/kinematics.hpp"
#include "hal/can_loopback.hpp"
#include "hal/canopen/canopen_master.hpp"
#include "sim/arm/sim_arm_bus.hpp"
#include "tests/support/angles.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

using canopen::DriveFault;
using canopen::LinkEvent;
using canopen::LinkState;

constexpr int kDrives = 5;
constexpr std::int64_t kLoopbackCycleMs = 10;

struct LoopbackRig {
  hal::CanLoopbackBus bus;
  canopen::CanopenMaster master;
  sim::SimArmBus sim;
  std::array<canopen::DriveConfig, kDrives> config{};
  std::array<sim::SimDriveParams, kDrives> params{};
  hal::CanLoopbackBus::Endpoint* master_port = nullptr;
  hal::CanLoopbackBus::Endpoint* spare_port = nullptr;  // a third node, for foreign frames
  std::int64_t now = 0;
  std::vector<canopen::MasterEvent> events;

  explicit LoopbackRig(std::function<void(LoopbackRig&)> tweak = {}) {
    const arm::JointLimits limits = arm::default_joint_limits();
    const arm::JointVector stow = arm::stow_pose();
    for (int i = 0; i < kDrives; ++i) {
      canopen::DriveConfig& c = config[i];
      c.node_id = static_cast<std::uint8_t>(i + 1);
      c.zero_counts = 10000 * (i + 1);
      c.direction = i % 2 == 0 ? 1 : -1;
      c.min_position_rad = limits.min_rad[i];
      c.max_position_rad = limits.max_rad[i];
      c.profile_velocity_rad_s = limits.max_velocity_rad_s[i];
      c.profile_acceleration_rad_s2 = limits.max_acceleration_rad_s2[i];
      params[i].node_id = c.node_id;
      params[i].initial_position_counts =
          c.zero_counts +
          c.direction * static_cast<std::int32_t>(std::lround(stow[i] * c.counts_per_rad));
    }
    if (tweak) tweak(*this);
    master_port = *bus.attach();
    spare_port = *bus.attach();
    auto drive_port = bus.attach();
    EXPECT_TRUE(master.configure(config, canopen::LinkTiming{}, *master_port).ok());
    EXPECT_TRUE(sim.configure(params, **drive_port).ok());
    sim.power_on(0);
  }

  void tick() {
    now += kLoopbackCycleMs;
    master.step(now);
    sim.step(now);
    canopen::MasterEvent e;
    while (master.pop_event(e)) events.push_back(e);
  }
  bool run_until(const std::function<bool()>& done, std::int64_t max_ms) {
    const std::int64_t end = now + max_ms;
    while (now < end) {
      tick();
      if (done()) return true;
    }
    return false;
  }
  void run_for(std::int64_t ms) {
    const std::int64_t end = now + ms;
    while (now < end) tick();
  }
  bool booted_and_enabled() {
    master.boot(now);
    if (!run_until([&] { return master.all_in(LinkState::operational); }, 3000)) return false;
    master.enable(now);
    return run_until([&] { return master.all_in(LinkState::ready); }, 1000);
  }
  int count(LinkEvent ev, std::uint8_t node) const {
    int n = 0;
    for (const auto& e : events) n += e.event == ev && e.node == node;
    return n;
  }
  bool has_fault_event(std::uint8_t node, DriveFault f) const {
    for (const auto& e : events) {
      if (e.node == node && e.event == LinkEvent::fault &&
          (e.detail >> 24) == static_cast<std::uint32_t>(f)) {
        return true;
      }
    }
    return false;
  }
  double sim_rad(int i) const {
    const auto& c = config[i];
    return c.direction * (sim.drive(i).position_counts() - c.zero_counts) / c.counts_per_rad;
  }
};

TEST(CanopenLoopback, BootConfigureEnableMoveAndStop) {
  auto rig = std::make_unique<LoopbackRig>();
  rig->master.boot(rig->now);
  ASSERT_TRUE(rig->run_until([&] { return rig->master.all_in(LinkState::operational); }, 3000));
  const std::int64_t boot_ms = rig->now;
  for (int i = 0; i < kDrives; ++i) {
    const std::uint8_t node = static_cast<std::uint8_t>(i + 1);
    EXPECT_EQ(rig->count(LinkEvent::booted, node), 1);
    EXPECT_EQ(rig->count(LinkEvent::configured, node), 1);
    EXPECT_EQ(rig->count(LinkEvent::operational, node), 1);
    EXPECT_EQ(rig->sim.drive(i).nmt_state(), canopen::NmtState::operational);
    EXPECT_EQ(rig->sim.drive(i).sdo_aborts_sent(), 0u);
    // The position read at configuration is the drive's (the stow pose).
    EXPECT_NEAR(rig->master.drive(i).position_rad(), arm::stow_pose()[i], 1e-5);
  }
  rig->master.enable(rig->now);
  ASSERT_TRUE(rig->run_until([&] { return rig->master.all_in(LinkState::ready); }, 1000));
  for (int i = 0; i < kDrives; ++i) {
    EXPECT_EQ(rig->sim.drive(i).drive_state(), canopen::DriveState::operation_enabled);
  }
  // Move every joint; track the fastest motion each drive made.
  const std::array<double, kDrives> target = {40 * test::kRadPerDeg, 50 * test::kRadPerDeg,
                                              70 * test::kRadPerDeg, 130 * test::kRadPerDeg,
                                              -20 * test::kRadPerDeg};
  ASSERT_TRUE(rig->master.set_targets(target).ok());
  std::array<double, kDrives> prev{}, fastest{};
  for (int i = 0; i < kDrives; ++i) prev[i] = rig->sim_rad(i);
  const std::int64_t move_start = rig->now;
  const bool arrived = rig->run_until(
      [&] {
        for (int i = 0; i < kDrives; ++i) {
          const double v = std::abs(rig->sim_rad(i) - prev[i]) / (kLoopbackCycleMs * 1e-3);
          fastest[i] = std::max(fastest[i], v);
          prev[i] = rig->sim_rad(i);
        }
        return rig->master.all_targets_reached();
      },
      10000);
  ASSERT_TRUE(arrived);
  const double move_s = static_cast<double>(rig->now - move_start) * 1e-3;
  for (int i = 0; i < kDrives; ++i) {
    EXPECT_NEAR(rig->sim_rad(i), target[i], 1e-3) << "joint " << i + 1;
    EXPECT_NEAR(rig->master.drive(i).position_rad(), target[i], 1e-3) << "joint " << i + 1;
    EXPECT_LE(fastest[i], 30 * test::kRadPerDeg * 1.05)
        << "joint " << i + 1;  // profile velocity 30 deg/s
  }
  // th4 moves 95 deg at 30 deg/s, 60 deg/s^2: 3.67 s plus the motor lag and handshakes.
  EXPECT_GT(move_s, 3.6);
  EXPECT_LT(move_s, 4.5);
  RecordProperty("boot_ms", std::to_string(boot_ms));
  RecordProperty("move_s", std::to_string(move_s));

  rig->master.quick_stop();
  ASSERT_TRUE(rig->run_until([&] { return rig->master.all_in(LinkState::quick_stopped); }, 100));
  rig->run_for(200);
  for (int i = 0; i < kDrives; ++i) {
    EXPECT_EQ(rig->sim.drive(i).drive_state(), canopen::DriveState::quick_stop_active);
    EXPECT_EQ(rig->count(LinkEvent::quick_stopped, static_cast<std::uint8_t>(i + 1)), 1);
  }
  rig->master.disable();
  rig->run_for(100);
  for (int i = 0; i < kDrives; ++i) {
    EXPECT_EQ(rig->sim.drive(i).drive_state(), canopen::DriveState::switch_on_disabled);
    EXPECT_EQ(rig->master.drive(i).state(), LinkState::operational);
  }
  EXPECT_FALSE(rig->master.any_fault());
  EXPECT_EQ(rig->master.counters().bad_frames, 0u);
  EXPECT_EQ(rig->master.counters().send_errors, 0u);
  EXPECT_EQ(rig->master.counters().events_dropped, 0u);
}

TEST(CanopenLoopback, QuickStopMidMoveHaltsEveryJoint) {
  auto rig = std::make_unique<LoopbackRig>();
  ASSERT_TRUE(rig->booted_and_enabled());
  const std::array<double, kDrives> target = {80 * test::kRadPerDeg, 80 * test::kRadPerDeg,
                                              20 * test::kRadPerDeg, 170 * test::kRadPerDeg,
                                              40 * test::kRadPerDeg};
  ASSERT_TRUE(rig->master.set_targets(target).ok());
  rig->run_for(1000);
  rig->master.quick_stop();
  rig->run_for(600);  // 0.5 rad/s stops in 0.17 s at 3 rad/s^2
  std::array<double, kDrives> held{};
  for (int i = 0; i < kDrives; ++i) held[i] = rig->sim_rad(i);
  rig->run_for(500);
  for (int i = 0; i < kDrives; ++i) {
    EXPECT_NEAR(rig->sim_rad(i), held[i], 1e-6) << "joint " << i + 1;
    EXPECT_GT(std::abs(rig->sim_rad(i) - target[i]), 0.1) << "joint " << i + 1 << " did not stop";
  }
  // Targets are refused while stopped; enable resumes where the arm is.
  EXPECT_EQ(rig->master.set_targets(target).code(), Errc::not_ready);
  rig->master.enable(rig->now);
  ASSERT_TRUE(rig->run_until([&] { return rig->master.all_in(LinkState::ready); }, 500));
  for (int i = 0; i < kDrives; ++i) EXPECT_NEAR(rig->master.drive(i).target_rad(), held[i], 1e-5);
}

// Runs a fault scenario: boot and enable, start a move, inject, and expect the
// master to report `fault` on drive `index` with a fault event, and every
// other drive quick-stopped.
void expect_fault_detected(LoopbackRig& rig, int index, DriveFault fault,
                           const std::function<void()>& inject, std::int64_t within_ms) {
  ASSERT_TRUE(rig.booted_and_enabled());
  const std::array<double, kDrives> target = {30 * test::kRadPerDeg, 30 * test::kRadPerDeg,
                                              100 * test::kRadPerDeg, 100 * test::kRadPerDeg,
                                              10 * test::kRadPerDeg};
  ASSERT_TRUE(rig.master.set_targets(target).ok());
  rig.run_for(300);
  inject();
  const std::int64_t t0 = rig.now;
  ASSERT_TRUE(rig.run_until([&] { return rig.master.any_fault(); }, within_ms))
      << "no fault within " << within_ms << " ms";
  ::testing::Test::RecordProperty("detected_after_ms", std::to_string(rig.now - t0));
  const auto& link = rig.master.drive(index);
  EXPECT_EQ(link.state(), LinkState::fault);
  EXPECT_EQ(link.fault(), fault) << canopen::drive_fault_name(link.fault());
  EXPECT_TRUE(rig.has_fault_event(static_cast<std::uint8_t>(index + 1), fault));
  rig.run_for(3 * kLoopbackCycleMs);
  for (int i = 0; i < kDrives; ++i) {
    if (i == index) continue;
    EXPECT_EQ(rig.master.drive(i).state(), LinkState::quick_stopped) << "drive " << i + 1;
  }
}

TEST(CanopenLoopback, AStoppedHeartbeatIsDetected) {
  auto rig = std::make_unique<LoopbackRig>();
  expect_fault_detected(
      *rig, 2, DriveFault::heartbeat_lost, [&] { rig->sim.drive(2).stop_heartbeat(true); }, 500);
}

TEST(CanopenLoopback, ADeadDriveIsDetectedByItsHeartbeat) {
  auto rig = std::make_unique<LoopbackRig>();
  expect_fault_detected(
      *rig, 0, DriveFault::heartbeat_lost, [&] { rig->sim.drive(0).power_off(); }, 500);
}

TEST(CanopenLoopback, AnEmergencyIsAFaultWithItsCode) {
  auto rig = std::make_unique<LoopbackRig>();
  expect_fault_detected(
      *rig, 3, DriveFault::emergency,
      [&] { rig->sim.inject_fault(3, canopen::emcy_code::kOverCurrent); }, 50);
  EXPECT_EQ(rig->master.drive(3).fault_detail(), canopen::emcy_code::kOverCurrent);
  EXPECT_EQ(rig->master.drive(3).last_emcy_code(), canopen::emcy_code::kOverCurrent);
  bool emcy_event = false;
  for (const auto& e : rig->events)
    emcy_event |= e.node == 4 && e.event == LinkEvent::emergency && e.detail == 0x2310;
  EXPECT_TRUE(emcy_event);
}

TEST(CanopenLoopback, AStalledJointIsAFollowingError) {
  auto rig = std::make_unique<LoopbackRig>();
  // The window is 0.05 rad: at 0.5 rad/s the stalled joint passes it in 0.1 s.
  expect_fault_detected(
      *rig, 1, DriveFault::following_error, [&] { rig->sim.drive(1).stall(true); }, 500);
  EXPECT_EQ(rig->sim.drive(1).drive_state(), canopen::DriveState::fault);
}

TEST(CanopenLoopback, ADriveThatWillNotEnableIsRefused) {
  auto rig = std::make_unique<LoopbackRig>();
  rig->sim.drive(4).refuse_enable(true);
  rig->master.boot(rig->now);
  ASSERT_TRUE(rig->run_until([&] { return rig->master.all_in(LinkState::operational); }, 3000));
  rig->master.enable(rig->now);
  ASSERT_TRUE(rig->run_until([&] { return rig->master.any_fault(); }, 1500));
  EXPECT_EQ(rig->master.drive(4).fault(), DriveFault::enable_refused);
  EXPECT_TRUE(rig->has_fault_event(5, DriveFault::enable_refused));
  // The drive never enabled; the master's quick stop then switched it off.
  EXPECT_EQ(rig->sim.drive(4).drive_state(), canopen::DriveState::switch_on_disabled);
  EXPECT_EQ(rig->master.drive(4).drive_state(), canopen::DriveState::switched_on);
}

TEST(CanopenLoopback, AWrongDeviceIsRefusedAtConfiguration) {
  auto rig = std::make_unique<LoopbackRig>(
      [](LoopbackRig& r) { r.params[1].supported_modes = 0x0000'0008; });  // CSP only
  rig->master.boot(rig->now);
  ASSERT_TRUE(rig->run_until([&] { return rig->master.any_fault(); }, 3000));
  EXPECT_EQ(rig->master.drive(1).fault(), DriveFault::wrong_device);
  EXPECT_EQ(rig->master.drive(1).fault_detail(), 0x0000'0008u);
  auto rig2 = std::make_unique<LoopbackRig>(
      [](LoopbackRig& r) { r.params[0].device_type = 0x0000'0191; });  // CiA 401 I/O
  rig2->master.boot(rig2->now);
  ASSERT_TRUE(rig2->run_until([&] { return rig2->master.any_fault(); }, 3000));
  EXPECT_EQ(rig2->master.drive(0).fault(), DriveFault::wrong_device);
}

TEST(CanopenLoopback, AMissingDriveTimesOutAtBoot) {
  auto rig = std::make_unique<LoopbackRig>();
  rig->sim.drive(2).power_off();
  rig->master.boot(rig->now);
  ASSERT_TRUE(
      rig->run_until([&] { return rig->master.drive(2).state() == LinkState::fault; }, 4000));
  EXPECT_EQ(rig->master.drive(2).fault(), DriveFault::boot_timeout);
}

TEST(CanopenLoopback, DrivesFaultWhenTheMasterGoesQuiet) {
  auto rig = std::make_unique<LoopbackRig>();
  ASSERT_TRUE(rig->booted_and_enabled());
  // The master stops (no step for 1 s): the drives' heartbeat consumers trip.
  for (int k = 0; k < 100; ++k) {
    rig->now += kLoopbackCycleMs;
    rig->sim.step(rig->now);
  }
  for (int i = 0; i < kDrives; ++i)
    EXPECT_EQ(rig->sim.drive(i).drive_state(), canopen::DriveState::fault);
  rig->tick();
  EXPECT_TRUE(rig->master.any_fault());
  EXPECT_EQ(rig->master.drive(0).fault(), DriveFault::emergency);
  EXPECT_EQ(rig->master.drive(0).fault_detail(), canopen::emcy_code::kHeartbeatConsumer);
}

TEST(CanopenLoopback, MalformedAndForeignFramesChangeNothing) {
  auto rig = std::make_unique<LoopbackRig>();
  ASSERT_TRUE(rig->booted_and_enabled());
  auto send = [&](std::uint32_t id, std::initializer_list<std::uint8_t> bytes) {
    hal::CanFrame f;
    f.id = id;
    for (auto b : bytes) f.data[f.len++] = b;
    ASSERT_TRUE(rig->spare_port->send(f).ok());
  };
  send(0x181, {0x37, 0x02});                       // TPDO of node 1, too short
  send(0x702, {0x05, 0x00});                       // heartbeat of node 2, too long
  send(0x703, {0x42});                             // heartbeat with no such state
  send(0x084, {0x10, 0x23});                       // EMCY of node 4, too short
  send(0x585, {0x60, 0x17, 0x10, 0, 0, 0, 0, 0});  // SDO answer nobody asked for
  send(0x190, {1, 2, 3, 4, 5, 6});                 // TPDO of node 16: not ours
  send(0x123, {1});                                // not CANopen at all
  const auto before = rig->master.counters();
  rig->run_for(50);
  const auto after = rig->master.counters();
  EXPECT_EQ(after.bad_frames - before.bad_frames, 5u);
  EXPECT_EQ(after.foreign_frames - before.foreign_frames, 2u);
  EXPECT_FALSE(rig->master.any_fault());
  EXPECT_TRUE(rig->master.all_in(LinkState::ready));
  int bad_events = 0;
  for (const auto& e : rig->events) bad_events += e.event == LinkEvent::bad_frame;
  EXPECT_EQ(bad_events, 5);
}

TEST(CanopenLoopback, BusOffIsReportedAndEndsInLostHeartbeats) {
  auto rig = std::make_unique<LoopbackRig>();
  ASSERT_TRUE(rig->booted_and_enabled());
  rig->bus.set_bus_off(*rig->master_port, true);
  ASSERT_TRUE(rig->run_until([&] { return rig->master.any_fault(); }, 1000));
  EXPECT_EQ(rig->master.bus_state(), hal::CanBusState::bus_off);
  bool bus_event = false;
  for (const auto& e : rig->events) {
    bus_event |= e.node == 0 && e.event == LinkEvent::bus_state &&
                 e.detail == static_cast<std::uint32_t>(hal::CanBusState::bus_off);
  }
  EXPECT_TRUE(bus_event);
  EXPECT_GT(rig->master.counters().send_errors, 0u);
  EXPECT_EQ(rig->master.drive(0).fault(), DriveFault::heartbeat_lost);
}

TEST(CanopenLoopback, SteadyStateMotionDoesNotAllocate) {
  auto rig = std::make_unique<LoopbackRig>();
  ASSERT_TRUE(rig->booted_and_enabled());
  rig->events.reserve(1024);
  test::HeapScope scope;
  std::array<double, kDrives> target = {0.2, 0.2, 1.5, 1.5, 0.1};
  for (int k = 0; k < 200; ++k) {
    target[0] = 0.2 + 0.001 * k;
    (void)rig->master.set_targets(target);
    rig->tick();
  }
  EXPECT_EQ(scope.allocations(), 0u);
  EXPECT_FALSE(rig->master.any_fault());
}

}  // namespace
}  // namespace petra
