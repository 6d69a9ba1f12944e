// The executive with the flight arm (FlightArm: service, CANopen master) over
// the loopback bus and the simulated drives: SELECT_ROI, EVALUATE, ARM_GOTO on
// a simulated scene's grind face; refusals; ABORT; a drive fault and the
// e-stop ending in SAFE. Telecommands and telemetry go over real UDP.
// GotoOnASimulatedScene... scripts the evaluation with the scene's true grind
// faces; TheFullChain... runs the flight image pipeline on the rendered pair.
#include <gtest/gtest.h>

#include <numbers>

#include <filesystem>

#include "fsw/arm/flight_arm.hpp"
#include "fsw/pipeline_factory.hpp"
#include "hal/can_loopback.hpp"
#include "sim/arm/sim_arm_bus.hpp"
#include "sim/arm/sim_arm_setup.hpp"
#include "sim/scene/scene.hpp"
#include "sim/scene/scene_geometry.hpp"
#include "sim/scene/scene_render.hpp"
#include "tests/sim/arm/executive_arm_rig.hpp"
#include "tests/support/angles.hpp"

namespace petra {
namespace {

using cmd::FunctionCode;
using test::ArmRig;
using test::ExecutiveHarness;
using test::start_motion;
tlm::GrindPlane plane_of(const sim::VisibleFacet& f) {
  tlm::GrindPlane p;
  for (int k = 0; k < 3; ++k) {
    p.normal[static_cast<std::size_t>(k)] = f.normal[k];
    p.centroid_mm[static_cast<std::size_t>(k)] = f.centroid[k];
  }
  p.area_mm2 = f.area_mm2;
  p.triangles = 100;
  return p;
}

// The grind faces of the first simulated scene (seed 1 up) with one the arm can reach.
std::vector<tlm::GrindPlane> scene_planes(int& reachable_rank, std::uint64_t& seed_used) {
  for (std::uint64_t seed = 1; seed < 40; ++seed) {
    sim::SceneOptions o;
    o.seed = seed;
    auto scene = sim::make_scene(o);
    if (!scene) continue;
    std::vector<tlm::GrindPlane> planes;
    reachable_rank = -1;
    for (const auto& f : sim::visible_facets(*scene)) {
      if (!f.grind_face) continue;
      planes.push_back(plane_of(f));
      arm::ApproachRequest r;
      r.centroid_mm = f.centroid;
      r.normal = f.normal;
      r.standoff_mm = 50;
      if (reachable_rank < 0 && arm::plan_approach(arm::rover_arm_geometry(),
                                                   arm::default_joint_limits(), r, arm::stow_pose())
                                    .ok()) {
        reachable_rank = static_cast<int>(planes.size()) - 1;
      }
    }
    if (reachable_rank >= 0) {
      seed_used = seed;
      return planes;
    }
  }
  return {};
}

TEST(ExecutiveArm, GotoOnASimulatedSceneReachesTheChosenPlane) {
  ArmRig rig;
  ASSERT_TRUE(rig.boot());
  int rank = -1;
  std::uint64_t seed = 0;
  const auto planes = scene_planes(rank, seed);
  ASSERT_GE(rank, 0) << "no simulated scene with a reachable grind face";
  ASSERT_TRUE(rig.evaluate(planes));
  const auto downlinked = rig.h.all<tlm::GrindPlane>();
  ASSERT_EQ(downlinked.size(), planes.size());
  const auto go = rig.goto_plane(rank, 50);
  ASSERT_TRUE(rig.until([&] { return rig.h.exec().mode() == Mode::ARM_MOVING; }, 20));
  ASSERT_TRUE(rig.until(
      [&] {
        return rig.h.has_ack(go.counter, AckStage::COMPLETED) ||
               rig.h.has_ack(go.counter, AckStage::FAILED);
      },
      4000));
  ASSERT_TRUE(rig.h.has_ack(go.counter, AckStage::COMPLETED));
  EXPECT_EQ(rig.h.exec().mode(), Mode::IDLE);
  EXPECT_TRUE(rig.event(EventId::ARM_MOTION_STARTED));
  EXPECT_TRUE(rig.event(EventId::ARM_REACHED));
  // The simulated encoders, through forward kinematics, against the downlinked plane.
  const tlm::GrindPlane& p = downlinked[static_cast<std::size_t>(rank)];
  const Eigen::Vector3d centroid(p.centroid_mm[0], p.centroid_mm[1], p.centroid_mm[2]);
  const Eigen::Vector3d normal(p.normal[0], p.normal[1], p.normal[2]);
  const arm::ToolPose tool = rig.sim_tool();
  const double tip_mm = (tool.tip_mm - centroid).norm();
  const double axis_deg =
      std::acos(std::clamp(-tool.axis.dot(normal), -1.0, 1.0)) / test::kRadPerDeg;
  RecordProperty("scene_seed", std::to_string(seed));
  RecordProperty("tip_error_mm", std::to_string(tip_mm));
  RecordProperty("axis_error_deg", std::to_string(axis_deg));
  EXPECT_LT(tip_mm, 1.0);
  EXPECT_LT(axis_deg, 0.5);
  // ARM_STATUS telemetry reports the same.
  rig.until([&] { return false; }, 110);  // past one housekeeping period
  const auto status = rig.h.all<tlm::ArmStatus>();
  ASSERT_FALSE(status.empty());
  const tlm::ArmStatus& s = status.back();
  EXPECT_EQ(s.state, static_cast<std::uint8_t>(fsw::arm::ArmState::holding));
  EXPECT_EQ(s.progress, static_cast<std::uint8_t>(fsw::arm::MotionProgress::reached));
  EXPECT_LT(s.tip_error_mm, 1.0f);
  EXPECT_EQ(s.moves_completed, 1u);
  EXPECT_NEAR(s.tip_mm[0], tool.tip_mm.x(), 0.01);
  // Then stow: backs out along the normal first, ends at (0, 0, 145, 35, 0).
  const auto stow = rig.h.make(FunctionCode::ARM_STOW);
  rig.h.send(stow);
  ASSERT_TRUE(rig.until([&] { return rig.h.has_ack(stow.counter, AckStage::COMPLETED); }, 4000));
}

// SELECT_ROI and EVALUATE with the flight pipeline on a rendered scene (seed 1,
// the demo's), then ARM_GOTO to the best-ranked plane the arm can reach.
TEST(ExecutiveArm, TheFullChainOnASimulatedSceneEndsOnTheChosenPlane) {
  ArmRig rig(R"(,"calib":"scene/calib.json")");
  sim::SceneOptions o;
  o.seed = 1;
  auto scene = sim::render_scene(o);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  const std::filesystem::path dir = rig.h.dir();
  ASSERT_TRUE(sim::write_scene(*scene, (dir / "scene").string()).ok());
  std::filesystem::copy_file(dir / "scene/left.pgm", dir / "camera/left_000.pgm",
                             std::filesystem::copy_options::overwrite_existing);
  std::filesystem::copy_file(dir / "scene/right.pgm", dir / "camera/right_000.pgm",
                             std::filesystem::copy_options::overwrite_existing);
  static hal::SystemClock clock;  // the job outlives the rig: static, as flight_pipeline() is
  rig.h.pipeline = fsw::flight_pipeline(clock);
  rig.h.budget = R"({"image_width":1024,"image_height":768})";  // the flight default
  ASSERT_TRUE(rig.boot());
  const Rect roi = scene->truth.roi;
  const auto sel = rig.h.make(FunctionCode::SELECT_ROI,
                              test::roi(roi.x, roi.y, roi.w, roi.h, scene->truth.planes));
  cmd::EvaluateArgs ev;
  ev.acquire = 1;
  const auto eval = rig.h.make(FunctionCode::EVALUATE, ev);
  rig.h.send(sel);
  rig.h.send(eval);
  ASSERT_TRUE(rig.until_wall(
      [&] {
        return rig.h.has_ack(eval.counter, AckStage::COMPLETED) ||
               rig.h.has_ack(eval.counter, AckStage::FAILED);
      },
      120));
  ASSERT_TRUE(rig.h.has_ack(eval.counter, AckStage::COMPLETED));
  const auto planes = rig.h.all<tlm::GrindPlane>();
  ASSERT_FALSE(planes.empty());
  int rank = -1;
  for (std::size_t i = 0; i < planes.size() && rank < 0; ++i) {
    arm::ApproachRequest r;
    r.centroid_mm = {planes[i].centroid_mm[0], planes[i].centroid_mm[1], planes[i].centroid_mm[2]};
    r.normal = {planes[i].normal[0], planes[i].normal[1], planes[i].normal[2]};
    r.standoff_mm = 50;
    if (arm::plan_approach(arm::rover_arm_geometry(), arm::default_joint_limits(), r,
                           arm::stow_pose())
            .ok())
      rank = static_cast<int>(i);
  }
  ASSERT_GE(rank, 0) << "none of the " << planes.size() << " planes is within the arm's reach";
  const auto go = rig.goto_plane(rank, 50);
  ASSERT_TRUE(rig.until(
      [&] {
        return rig.h.has_ack(go.counter, AckStage::COMPLETED) ||
               rig.h.has_ack(go.counter, AckStage::FAILED);
      },
      4000));
  ASSERT_TRUE(rig.h.has_ack(go.counter, AckStage::COMPLETED));
  const tlm::GrindPlane& p = planes[static_cast<std::size_t>(rank)];
  const Eigen::Vector3d centroid(p.centroid_mm[0], p.centroid_mm[1], p.centroid_mm[2]);
  const Eigen::Vector3d normal(p.normal[0], p.normal[1], p.normal[2]);
  const arm::ToolPose tool = rig.sim_tool();
  const double tip_mm = (tool.tip_mm - centroid).norm();
  const double axis_deg =
      std::acos(std::clamp(-tool.axis.dot(normal), -1.0, 1.0)) / test::kRadPerDeg;
  RecordProperty("planes", std::to_string(planes.size()));
  RecordProperty("rank", std::to_string(rank));
  RecordProperty("tip_error_mm", std::to_string(tip_mm));
  RecordProperty("axis_error_deg", std::to_string(axis_deg));
  EXPECT_LT(tip_mm, 1.0);
  EXPECT_LT(axis_deg, 0.5);
}

TEST(ExecutiveArm, AnUnreachablePlaneFailsWithArmRefused) {
  ArmRig rig;
  ASSERT_TRUE(rig.boot());
  tlm::GrindPlane far;
  far.normal = {0, 0, 1};
  far.centroid_mm = {0, 1600, 50};
  ASSERT_TRUE(rig.evaluate({far}));
  const auto go = rig.goto_plane(0, 50);
  ASSERT_TRUE(rig.until([&] { return rig.h.has_ack(go.counter, AckStage::FAILED); }, 50));
  EXPECT_EQ(rig.h.acks_for(go.counter).back().reason,
            static_cast<std::uint8_t>(Reason::ARM_REFUSED));
  EXPECT_TRUE(rig.event(EventId::ARM_REFUSED));
  EXPECT_EQ(rig.h.exec().mode(), Mode::IDLE);
  const auto bad_rank = rig.goto_plane(3, 50);
  ASSERT_TRUE(rig.until([&] { return rig.h.has_ack(bad_rank.counter, AckStage::FAILED); }, 50));
  EXPECT_EQ(rig.h.acks_for(bad_rank.counter).back().reason,
            static_cast<std::uint8_t>(Reason::NO_SUCH_PLANE));
}

TEST(ExecutiveArm, AbortQuickStopsTheDrives) {
  ArmRig rig;
  ASSERT_TRUE(rig.boot());
  cmd::Command go;
  ASSERT_NO_FATAL_FAILURE(start_motion(rig, go));
  const auto abort = rig.h.make(FunctionCode::ABORT);
  rig.h.send(abort);
  ASSERT_TRUE(rig.until([&] { return rig.h.has_ack(abort.counter, AckStage::COMPLETED); }, 50));
  ASSERT_TRUE(rig.h.has_ack(go.counter, AckStage::FAILED));  // before .back()
  EXPECT_EQ(rig.h.acks_for(go.counter).back().reason, static_cast<std::uint8_t>(Reason::ABORTED));
  EXPECT_EQ(rig.h.exec().mode(), Mode::IDLE);
  rig.until([&] { return false; }, 30);
  for (int j = 0; j < 5; ++j)
    EXPECT_EQ(rig.drives.drive(j).drive_state(), canopen::DriveState::quick_stop_active);
  EXPECT_TRUE(rig.event(EventId::ARM_STOPPED));
}

TEST(ExecutiveArm, ALostDriveHeartbeatEndsInSafeWithAnEvent) {
  ArmRig rig;
  ASSERT_TRUE(rig.boot());
  cmd::Command go;
  ASSERT_NO_FATAL_FAILURE(start_motion(rig, go));
  rig.drives.drive(2).stop_heartbeat(true);
  ASSERT_TRUE(rig.until([&] { return rig.h.exec().mode() == Mode::SAFE; }, 100));
  EXPECT_TRUE(rig.event(EventId::ARM_DRIVE_FAULT));
  EXPECT_TRUE(rig.h.has_ack(go.counter, AckStage::FAILED));
  bool right_args = false;
  for (const auto& e : rig.h.all<tlm::Event>()) {
    right_args |= e.event_id == static_cast<std::uint16_t>(EventId::ARM_DRIVE_FAULT) &&
                  e.args[0] == 3 &&
                  e.args[1] == static_cast<std::int32_t>(canopen::DriveFault::heartbeat_lost);
  }
  EXPECT_TRUE(right_args);
  rig.until([&] { return false; }, 30);
  EXPECT_EQ(rig.drives.drive(0).drive_state(), canopen::DriveState::quick_stop_active);
  // In SAFE the arm refuses to move until it is reset.
  const auto stow = rig.h.make(FunctionCode::ARM_STOW);
  rig.h.send(stow);
  ASSERT_TRUE(rig.until([&] { return rig.h.has_ack(stow.counter, AckStage::FAILED); }, 50));
  EXPECT_EQ(rig.h.acks_for(stow.counter).back().reason,
            static_cast<std::uint8_t>(Reason::ARM_NOT_READY));
  // The drive recovers; leaving SAFE reboots the drives and the arm can stow.
  rig.drives.drive(2).stop_heartbeat(false);
  cmd::SetModeArgs idle;
  idle.mode = static_cast<std::uint8_t>(Mode::IDLE);
  const auto leave = rig.h.make(FunctionCode::SET_MODE, idle);
  rig.h.send(leave);
  ASSERT_TRUE(rig.until([&] { return rig.h.has_ack(leave.counter, AckStage::COMPLETED); }, 50));
  ASSERT_TRUE(rig.until(
      [&] {
        int ready = 0;
        for (const auto& e : rig.h.all<tlm::Event>())
          ready += e.event_id == static_cast<std::uint16_t>(EventId::ARM_READY);
        return ready == 2;
      },
      500));
  const auto stow2 = rig.h.make(FunctionCode::ARM_STOW);
  rig.h.send(stow2);
  ASSERT_TRUE(rig.until([&] { return rig.h.has_ack(stow2.counter, AckStage::COMPLETED); }, 4000));
}

TEST(ExecutiveArm, TheEStopEndsInAQuickStopAndSafe) {
  ArmRig rig;
  ASSERT_TRUE(rig.boot());
  cmd::Command go;
  ASSERT_NO_FATAL_FAILURE(start_motion(rig, go));
  rig.estop.set(true);
  ASSERT_TRUE(rig.until([&] { return rig.h.exec().mode() == Mode::SAFE; }, 5));
  EXPECT_TRUE(rig.event(EventId::ESTOP_ASSERTED));
  EXPECT_TRUE(rig.h.has_ack(go.counter, AckStage::FAILED));
  rig.until([&] { return false; }, 30);
  for (int j = 0; j < 5; ++j)
    EXPECT_EQ(rig.drives.drive(j).drive_state(), canopen::DriveState::quick_stop_active);
  // While the e-stop is held, the arm does not move, not even to stow.
  const auto stow = rig.h.make(FunctionCode::ARM_STOW);
  rig.h.send(stow);
  ASSERT_TRUE(rig.until([&] { return rig.h.has_ack(stow.counter, AckStage::FAILED); }, 50));
  EXPECT_EQ(rig.h.acks_for(stow.counter).back().reason,
            static_cast<std::uint8_t>(Reason::ARM_NOT_READY));
  rig.estop.set(false);
  rig.until([&] { return false; }, 2);  // the executive reads the line once per cycle
  const auto stow2 = rig.h.make(FunctionCode::ARM_STOW);
  rig.h.send(stow2);
  ASSERT_TRUE(rig.until([&] { return rig.h.has_ack(stow2.counter, AckStage::COMPLETED); }, 4000));
  int stopped = 0;
  for (const auto& e : rig.h.all<tlm::Event>())
    stopped += e.event_id == static_cast<std::uint16_t>(EventId::ARM_STOPPED);
  EXPECT_EQ(stopped, 1);
}

}  // namespace
}  // namespace petra
