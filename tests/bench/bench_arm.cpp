// Arm computation per control cycle: forward and inverse kinematics, one
// straight-approach set-point (IK), a whole approach plan, and one CANopen
// master cycle with five simulated drives on the loopback bus.
#include <benchmark/benchmark.h>

#include <memory>
#include <numbers>

#include "algo/arm/arm_trajectory.hpp"
#include "hal/can_loopback.hpp"
#include "hal/canopen/canopen_master.hpp"
#include "sim/arm/sim_arm_bus.hpp"
#include "sim/arm/sim_arm_setup.hpp"

namespace {

using namespace petra;
constexpr double kDeg = std::numbers::pi / 180.0;

arm::JointVector pose() {
  arm::JointVector q;
  q << 35 * kDeg, 25 * kDeg, 100 * kDeg, 80 * kDeg, -10 * kDeg;
  return q;
}

void BM_ForwardKinematics(benchmark::State& state) {
  const arm::ArmGeometry g = arm::rover_arm_geometry();
  arm::JointVector q = pose();
  for (auto _ : state) {
    q[0] += 1e-9;
    benchmark::DoNotOptimize(arm::forward_kinematics(g, q));
  }
}
BENCHMARK(BM_ForwardKinematics);

void BM_InverseKinematics(benchmark::State& state) {
  const arm::ArmGeometry g = arm::rover_arm_geometry();
  const arm::JointLimits l = arm::default_joint_limits();
  const arm::ToolPose t = arm::forward_kinematics(g, pose());
  arm::ToolTarget target{t.tip_mm, t.axis};
  for (auto _ : state) {
    target.tip_mm.x() += 1e-9;
    benchmark::DoNotOptimize(arm::inverse_kinematics(g, l, target, arm::stow_pose()));
  }
}
BENCHMARK(BM_InverseKinematics);

void BM_PlanApproach(benchmark::State& state) {
  const arm::ArmGeometry g = arm::rover_arm_geometry();
  const arm::JointLimits l = arm::default_joint_limits();
  const arm::ToolPose t = arm::forward_kinematics(g, pose());
  arm::ApproachRequest r;
  r.centroid_mm = t.tip_mm;
  r.normal = -t.axis;
  r.standoff_mm = 50;
  for (auto _ : state) benchmark::DoNotOptimize(arm::plan_approach(g, l, r, arm::stow_pose()));
}
BENCHMARK(BM_PlanApproach);

// One control cycle of the master with five drives answering (loopback, in process).
void BM_MasterCycleWithFiveDrives(benchmark::State& state) {
  auto bus = std::make_unique<hal::CanLoopbackBus>();
  auto m = bus->attach();
  auto d = bus->attach();
  auto master = std::make_unique<canopen::CanopenMaster>();
  auto drives = std::make_unique<sim::SimArmBus>();
  const auto configs = sim::default_arm_drive_configs();
  const std::array<double, 5> start = {0, 0, 145 * kDeg, 35 * kDeg, 0};
  if (!master->configure(configs, canopen::LinkTiming{}, **m).ok() ||
      !drives->configure(sim::sim_params_at(configs, start), **d).ok()) {
    state.SkipWithError("setup");
    return;
  }
  std::int64_t now = 0;
  drives->power_on(now);
  master->boot(now);
  master->enable(now);
  for (int k = 0; k < 200 && !master->all_in(canopen::LinkState::ready); ++k) {
    now += 10;
    master->step(now);
    drives->step(now);
  }
  if (!master->all_in(canopen::LinkState::ready)) {
    state.SkipWithError("drives not ready");
    return;
  }
  std::int64_t master_ns = 0;
  for (auto _ : state) {
    now += 10;
    master->step(now);
    state.PauseTiming();  // the drives are the simulated world, not flight code
    drives->step(now);
    state.ResumeTiming();
  }
  (void)master_ns;
}
BENCHMARK(BM_MasterCycleWithFiveDrives);

}  // namespace

BENCHMARK_MAIN();
