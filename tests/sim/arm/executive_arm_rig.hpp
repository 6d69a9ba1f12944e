// The executive with the flight arm over the loopback bus and the five
// simulated drives, driven cycle by cycle (tests/sim/arm/test_executive_arm*.cpp).
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <numbers>
#include <thread>

#include "fsw/arm/flight_arm.hpp"
#include "hal/can_loopback.hpp"
#include "sim/arm/sim_arm_bus.hpp"
#include "sim/arm/sim_arm_setup.hpp"
#include "tests/fsw/executive_harness.hpp"

namespace petra::test {

using cmd::FunctionCode;
inline constexpr double kArmDeg = std::numbers::pi / 180.0;

class ManualClock final : public hal::Clock {
 public:
  std::int64_t monotonic_ns() const override { return now_ns; }
  std::int64_t realtime_ns() const override { return now_ns; }
  std::int64_t now_ns = 1'000'000'000;
};

struct ArmRig {
  hal::CanLoopbackBus bus;
  ManualClock arm_clock;
  fsw::arm::FlightArm arm;
  sim::SimArmBus drives;
  hal::SettableInput estop;
  hal::CanLoopbackBus::Endpoint* master_port = nullptr;
  ExecutiveHarness h;

  explicit ArmRig(std::string extra_config = "") : h(std::move(extra_config)) {
    auto a = bus.attach();
    auto d = bus.attach();
    master_port = *a;
    const arm::JointVector stow = arm::stow_pose();
    const std::array<double, 5> pose = {stow[0], stow[1], stow[2], stow[3], stow[4]};
    EXPECT_TRUE(
        drives.configure(sim::sim_params_at(sim::default_arm_drive_configs(), pose), **d).ok());
    drives.power_on(arm_clock.now_ns / 1000000);
    EXPECT_TRUE(arm.init(fsw::arm::ArmServiceConfig{}, **a, arm_clock).ok());
    h.arm = &arm;
    h.estop = &estop;
  }
  // One executive cycle; the arm's time and the drives advance 10 ms with it.
  void cycle() {
    arm_clock.now_ns += 10'000'000;
    h.exec().run_cycle();
    drives.step(arm_clock.now_ns / 1000000);
    h.drain();
  }
  template <class Pred>
  bool until(Pred pred, int max_cycles) {
    for (int i = 0; i < max_cycles; ++i) {
      cycle();
      if (pred()) return true;
    }
    return false;
  }
  // Waits for work done beside the loop (the pipeline job's worker thread):
  // cycles with a 1 ms pause for at most `seconds` of wall time, so the bound
  // does not depend on how fast the loop spins against the worker under load.
  template <class Pred>
  bool until_wall(Pred pred, int seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
    while (std::chrono::steady_clock::now() < end) {
      cycle();
      if (pred()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return false;
  }
  bool event(EventId id) const { return h.has_event(static_cast<std::uint16_t>(id)); }
  arm::ToolPose sim_tool() const {
    const auto configs = sim::default_arm_drive_configs();
    arm::JointVector q;
    for (int j = 0; j < 5; ++j) {
      q[j] = canopen::counts_to_position(
          configs[j], static_cast<std::int32_t>(std::lround(drives.drive(j).position_counts())));
    }
    return arm::forward_kinematics(arm::rover_arm_geometry(), q);
  }
  bool boot() {
    if (!h.boot().ok()) return false;
    return until([&] { return event(EventId::ARM_READY); }, 500);
  }
  // SELECT_ROI + EVALUATE: the scripted job answers with `planes`.
  bool evaluate(const std::vector<tlm::GrindPlane>& planes) {
    h.job.script = fsw::EvalOutput{};
    for (const auto& p : planes) (void)h.job.script.planes.push_back(p);
    const auto sel = h.make(FunctionCode::SELECT_ROI,
                            test::roi(20, 10, 100, 80, static_cast<int>(planes.size())));
    cmd::EvaluateArgs ev;
    ev.acquire = 1;
    const auto eval = h.make(FunctionCode::EVALUATE, ev);
    h.send(sel);
    h.send(eval);
    return until([&] { return h.has_ack(eval.counter, AckStage::COMPLETED); }, 2000);
  }
  cmd::Command goto_plane(int rank, double standoff_mm) {
    cmd::ArmGotoArgs a;
    a.plane_rank = static_cast<std::uint8_t>(rank);
    a.standoff_mm = static_cast<float>(standoff_mm);
    const auto c = h.make(FunctionCode::ARM_GOTO, a);
    h.send(c);
    return c;
  }
};

// Starts a goto towards a reachable plane and runs 2 s of it.
inline void start_motion(ArmRig& rig, cmd::Command& go) {
  tlm::GrindPlane p;
  const arm::ToolPose t = arm::forward_kinematics(arm::rover_arm_geometry(), [] {
    arm::JointVector q;
    q << 35 * kArmDeg, 25 * kArmDeg, 100 * kArmDeg, 80 * kArmDeg, -10 * kArmDeg;
    return q;
  }());
  for (int k = 0; k < 3; ++k) {
    p.centroid_mm[static_cast<std::size_t>(k)] = t.tip_mm[k];
    p.normal[static_cast<std::size_t>(k)] = -t.axis[k];
  }
  ASSERT_TRUE(rig.evaluate({p}));
  go = rig.goto_plane(0, 50);
  ASSERT_TRUE(rig.until([&] { return rig.h.exec().mode() == Mode::ARM_MOVING; }, 20));
  rig.until([&] { return false; }, 200);
  ASSERT_EQ(rig.h.exec().mode(), Mode::ARM_MOVING);
}

}  // namespace petra::test
