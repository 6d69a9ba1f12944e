// The executive's reaction to camera faults (docs/hal.md "Faults"): a broken
// frame, a timeout or a pair outside the skew is retried, and after
// Executive::kCameraAttempts failures the command fails with CAMERA_ERROR; a
// lost device is not retried. Each failure raises CAMERA_FAULT; the mode is
// unchanged (IDLE). The camera here is a scripted stand-in for the V4L2 one.
#include <gtest/gtest.h>

#include <deque>
#include <fstream>

#include "tests/fsw/executive_harness.hpp"

namespace petra {
namespace {

using cmd::FunctionCode;
using test::ExecutiveHarness;

// Answers acquire() from a script of error codes; Errc::ok (none left) = a good pair.
class ScriptedCamera final : public hal::StereoCamera {
 public:
  const char* name() const override { return "scripted"; }
  int width() const override { return ExecutiveHarness::kWidth; }
  int height() const override { return ExecutiveHarness::kHeight; }
  Result<hal::FrameMeta> acquire(Gray8View left, Gray8View right) override {
    ++calls;
    if (!script.empty()) {
      const Errc e = script.front();
      script.pop_front();
      return Error::make(e, "scripted camera fault");
    }
    for (int y = 0; y < left.height(); ++y)
      for (int x = 0; x < left.width(); ++x) {
        left(x, y) = static_cast<std::uint8_t>(x + y);
        right(x, y) = static_cast<std::uint8_t>(x + y + 3);
      }
    hal::FrameMeta m;
    m.sequence = ++good;
    return m;
  }
  std::deque<Errc> script;
  int calls = 0;
  std::uint32_t good = 0;
};

struct CameraRig {
  ScriptedCamera camera;
  ExecutiveHarness h;
  CameraRig() {
    h.camera = &camera;
    EXPECT_TRUE(h.boot().ok());
  }
  // Sends ACQUIRE and returns its final acknowledgement stage.
  AckStage acquire() {
    const auto c = h.make(FunctionCode::ACQUIRE);
    h.send(c);
    EXPECT_TRUE(h.cycle_until([&] {
      return h.has_ack(c.counter, AckStage::COMPLETED) || h.has_ack(c.counter, AckStage::FAILED);
    }));
    last_reason = h.acks_for(c.counter).back().reason;
    return static_cast<AckStage>(h.acks_for(c.counter).back().stage);
  }
  int camera_faults(Errc code) const {
    int n = 0;
    for (const auto& e : h.all<tlm::Event>())
      n += e.event_id == static_cast<std::uint16_t>(EventId::CAMERA_FAULT) &&
           e.args[0] == static_cast<std::int32_t>(code);
    return n;
  }
  std::uint8_t last_reason = 0;
};

TEST(ExecutiveCameraFaults, ABrokenFrameIsRetriedAndTheCommandCompletes) {
  CameraRig rig;
  rig.camera.script = {Errc::parse_error};
  EXPECT_EQ(rig.acquire(), AckStage::COMPLETED);
  EXPECT_EQ(rig.camera.calls, 2);
  EXPECT_EQ(rig.camera_faults(Errc::parse_error), 1);
  EXPECT_EQ(rig.h.exec().mode(), Mode::IDLE);
  EXPECT_EQ(rig.h.exec().loop_counters().frames, 1u);
}

TEST(ExecutiveCameraFaults, RepeatedTimeoutsFailTheCommandWithCameraErrorAndKeepTheMode) {
  CameraRig rig;
  rig.camera.script = {Errc::timeout, Errc::timeout, Errc::timeout, Errc::timeout};
  EXPECT_EQ(rig.acquire(), AckStage::FAILED);
  EXPECT_EQ(rig.last_reason, static_cast<std::uint8_t>(Reason::CAMERA_ERROR));
  EXPECT_EQ(rig.camera.calls, fsw::Executive::kCameraAttempts);
  EXPECT_EQ(rig.camera_faults(Errc::timeout), fsw::Executive::kCameraAttempts);
  EXPECT_EQ(rig.h.exec().mode(), Mode::IDLE);
  // The camera recovers: the next command gets a pair.
  rig.camera.script.clear();
  EXPECT_EQ(rig.acquire(), AckStage::COMPLETED);
}

TEST(ExecutiveCameraFaults, ALostDeviceIsNotRetried) {
  CameraRig rig;
  rig.camera.script = {Errc::io_error, Errc::io_error};
  EXPECT_EQ(rig.acquire(), AckStage::FAILED);
  EXPECT_EQ(rig.last_reason, static_cast<std::uint8_t>(Reason::CAMERA_ERROR));
  EXPECT_EQ(rig.camera.calls, 1);
  EXPECT_EQ(rig.camera_faults(Errc::io_error), 1);
  EXPECT_EQ(rig.h.exec().mode(), Mode::IDLE);
  // EVALUATE with acquisition is refused the same way, without starting the pipeline.
  const auto sel = rig.h.make(FunctionCode::SELECT_ROI, test::roi(20, 10, 100, 80, 1));
  cmd::EvaluateArgs ev;
  ev.acquire = 1;
  const auto eval = rig.h.make(FunctionCode::EVALUATE, ev);
  rig.h.send(sel);
  rig.h.send(eval);
  ASSERT_TRUE(rig.h.cycle_until([&] { return rig.h.has_ack(eval.counter, AckStage::FAILED); }));
  EXPECT_EQ(rig.h.acks_for(eval.counter).back().reason,
            static_cast<std::uint8_t>(Reason::CAMERA_ERROR));
  EXPECT_EQ(rig.h.exec().loop_counters().evaluations, 0u);
}

// Sends ACQUIRE and returns its final acknowledgement stage.
AckStage acquire(ExecutiveHarness& h) {
  const auto c = h.make(FunctionCode::ACQUIRE);
  h.send(c);
  EXPECT_TRUE(h.cycle_until([&] {
    return h.has_ack(c.counter, AckStage::COMPLETED) || h.has_ack(c.counter, AckStage::FAILED);
  }));
  return static_cast<AckStage>(h.acks_for(c.counter).back().stage);
}

TEST(ExecutiveCameraFaults, TheFileCameraMovesPastACorruptPairWithAnEvent) {
  ExecutiveHarness h;  // its file camera: pair 000, then these two
  const auto cam = h.dir() / "camera";
  test::write_pgm((cam / "left_001.pgm").string(), ExecutiveHarness::kWidth,
                  ExecutiveHarness::kHeight, 1);
  std::ofstream(cam / "right_001.pgm", std::ios::binary)
      << "P5\n" << ExecutiveHarness::kWidth << " " << ExecutiveHarness::kHeight << "\n255\nabc";
  test::write_pgm((cam / "left_002.pgm").string(), ExecutiveHarness::kWidth,
                  ExecutiveHarness::kHeight, 2);
  test::write_pgm((cam / "right_002.pgm").string(), ExecutiveHarness::kWidth,
                  ExecutiveHarness::kHeight, 7);
  ASSERT_TRUE(h.boot().ok());
  // Three passes over the folder: each pass meets the corrupt pair once.
  for (int i = 0; i < 6; ++i) EXPECT_EQ(acquire(h), AckStage::COMPLETED) << "ACQUIRE " << i;
  int faults = 0;
  for (const auto& e : h.all<tlm::Event>())
    faults += e.event_id == static_cast<std::uint16_t>(EventId::CAMERA_FAULT) &&
              e.args[0] == static_cast<std::int32_t>(Errc::parse_error);
  // Pairs 000, 002, 000, 002, ...: pair 001 is met (and reported) every other command.
  EXPECT_EQ(faults, 3);
  EXPECT_EQ(h.exec().loop_counters().frames, 6u);
}

}  // namespace
}  // namespace petra
