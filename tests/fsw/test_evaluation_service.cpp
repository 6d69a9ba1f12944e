// The evaluation service through its port (fsw/evaluation_port.hpp), with the
// scripted job on the real worker thread and no executive: start, poll,
// abort, status, and the refusals (no selection, no pipeline, busy).
#include <time.h>

#include <chrono>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "fsw/evaluation_service.hpp"
#include "hal/clock.hpp"
#include "tests/fsw/scripted_pipeline_job.hpp"

namespace petra::test {
namespace {

constexpr int kWidth = 64;
constexpr int kHeight = 48;

cmd::SelectRoiArgs roi_args(int x, int y, int w, int h, int planes) {
  cmd::SelectRoiArgs a;
  a.x_px = static_cast<std::uint16_t>(x);
  a.y_px = static_cast<std::uint16_t>(y);
  a.w_px = static_cast<std::uint16_t>(w);
  a.h_px = static_cast<std::uint16_t>(h);
  a.planes = static_cast<std::uint8_t>(planes);
  return a;
}

fsw::EvalOutput two_service_planes() {
  fsw::EvalOutput o;
  tlm::GrindPlane a;
  a.normal = {0.0, -0.6, -0.8};
  a.centroid_mm = {12.5, -30.25, 812.0};
  a.area_mm2 = 1530.5;
  tlm::GrindPlane b = a;
  b.area_mm2 = 900.0;
  (void)o.planes.push_back(a);
  (void)o.planes.push_back(b);
  return o;
}

// The service with everything it is wired to, each buffer sized here.
class ServiceRig {
 public:
  explicit ServiceRig(bool with_job = true) {
    queue_.init(queue_mem_, lengths_);
    events_.init(&queue_, &clock_);
    const auto sizes = fsw::ProductStreamer::bytes_needed(kWidth, kHeight, 100);
    std::array<std::span<std::uint8_t>, fsw::kProductKinds> spans{};
    for (std::size_t k = 0; k < fsw::kProductKinds; ++k) {
      product_mem_[k].resize(sizes[k]);
      spans[k] = product_mem_[k];
    }
    products_.init(spans, &events_);
    health_.reset(clock_.monotonic_ns());
    fsw::EvaluationWiring w;
    w.job = with_job ? &job : nullptr;
    w.budget = fsw::JobBudget{kWidth, kHeight, 100};
    arena_.resize(job.arena_bytes(w.budget));
    w.arena = arena_;
    w.worker_stack_bytes = 256 * 1024;
    w.health = &health_;
    w.clock = &clock_;
    w.params = &params;
    w.events = &events_;
    w.queue = &queue_;
    w.products = &products_;
    EXPECT_TRUE(service.init(w).ok());
  }
  ~ServiceRig() { service.shutdown(); }

  fsw::EvalFrame frame(std::uint32_t acquire_us = 0) const {
    return {7, ConstGray8View(left_.data(), kWidth, kHeight),
            ConstGray8View(right_.data(), kWidth, kHeight), acquire_us};
  }
  // Polls as the executive's pipeline rate group does, until the run is no longer RUNNING.
  fsw::EvalProgress settle() {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    fsw::EvalProgress p = service.poll();
    while (p == fsw::EvalProgress::RUNNING && std::chrono::steady_clock::now() < end) {
      nap();
      p = service.poll();
    }
    return p;
  }
  // Polls until the worker is free (a finished run counts as busy until polled);
  // false if any poll reported something other than IDLE.
  bool unwind() {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    bool all_idle = true;
    while (service.status().running && std::chrono::steady_clock::now() < end) {
      nap();
      all_idle = service.poll() == fsw::EvalProgress::IDLE && all_idle;
    }
    return all_idle && !service.status().running;
  }
  std::size_t events(EventId id) const { return events_.count(static_cast<std::uint16_t>(id)); }
  // Decodes and removes every queued packet.
  template <class T>
  std::vector<T> drain() {
    std::vector<T> out;
    while (!queue_.empty()) {
      auto p = tlm::decode_tm(queue_.front());
      if (p.ok())
        if (const T* t = std::get_if<T>(&p->body)) out.push_back(*t);
      queue_.pop();
    }
    return out;
  }

  ScriptedPipelineJob job;
  fsw::ParamTable params;
  fsw::EvaluationService service;

 private:
  static void nap() {
    timespec ts{0, 1000000};
    nanosleep(&ts, nullptr);
  }

  hal::SystemClock clock_;
  std::vector<std::uint8_t> queue_mem_ = std::vector<std::uint8_t>(tlm::TlmQueue::bytes_for(64));
  std::vector<std::uint16_t> lengths_ = std::vector<std::uint16_t>(64);
  tlm::TlmQueue queue_;
  fsw::EventLog events_;
  std::array<std::vector<std::uint8_t>, fsw::kProductKinds> product_mem_;
  fsw::ProductStreamer products_;
  fsw::Health health_;
  std::vector<std::byte> arena_;
  std::vector<std::uint8_t> left_ = std::vector<std::uint8_t>(kWidth * kHeight, 40);
  std::vector<std::uint8_t> right_ = std::vector<std::uint8_t>(kWidth * kHeight, 60);
};

TEST(EvaluationService, RefusesToStartWithoutASelection) {
  ServiceRig rig;
  EXPECT_EQ(rig.service.refusal(), Reason::NO_ROI);
  EXPECT_FALSE(rig.service.start(rig.frame(), ::petra::arm::stow_pose()).ok());
  EXPECT_EQ(rig.service.poll(), fsw::EvalProgress::IDLE);
  EXPECT_FALSE(rig.service.status().running);
  EXPECT_EQ(rig.job.runs.load(), 0);
}

TEST(EvaluationService, RefusesToStartWithoutAPipeline) {
  ServiceRig rig(false);
  rig.service.select(fsw::selection_from(roi_args(8, 4, 32, 24, 2)));
  EXPECT_EQ(rig.service.refusal(), Reason::NO_PIPELINE);
  EXPECT_FALSE(rig.service.start(rig.frame(), ::petra::arm::stow_pose()).ok());
}

// The selection reaches the job as SELECT_ROI built it, with MATCH_METHOD as its method;
// the result is published with each plane stamped, and kept for ARM_GOTO.
TEST(EvaluationService, StartsPollsAndPublishesTheResult) {
  ServiceRig rig;
  rig.job.script = two_service_planes();
  ASSERT_TRUE(rig.params.set(static_cast<std::uint16_t>(ParamId::MATCH_METHOD), 1).ok());
  cmd::SelectRoiArgs a = roi_args(8, 4, 32, 24, 3);
  a.has_click = 1;
  a.click_u_px = 20;
  a.click_v_px = 10;
  rig.service.select(fsw::selection_from(a));
  EXPECT_EQ(rig.service.refusal(), Reason::NONE);
  ASSERT_TRUE(rig.service.start(rig.frame(1234), ::petra::arm::stow_pose()).ok());
  EXPECT_EQ(rig.settle(), fsw::EvalProgress::COMPLETED);
  EXPECT_EQ(rig.service.poll(), fsw::EvalProgress::IDLE);  // once

  const PipelineRequest& sent = rig.job.last_request.selection;
  EXPECT_EQ(sent.roi, (Rect{8, 4, 32, 24}));
  EXPECT_EQ(sent.planes, 3);
  EXPECT_TRUE(sent.has_click);
  EXPECT_EQ(sent.click_u, 20);
  EXPECT_EQ(sent.click_v, 10);
  EXPECT_EQ(sent.method, MatchMethod::graph_cut);
  EXPECT_EQ(rig.job.last_request.eval_id, 1u);
  EXPECT_EQ(rig.job.last_request.frame, 7u);

  const fsw::EvalStatus s = rig.service.status();
  EXPECT_FALSE(s.running);
  EXPECT_EQ(s.step_us[static_cast<std::size_t>(fsw::Step::ACQUIRE)], 1234u);
  EXPECT_EQ(s.step_us[static_cast<std::size_t>(fsw::Step::MATCH)], 40u);  // the job's own
  EXPECT_GT(s.arena_bytes, 0u);
  ASSERT_NE(rig.service.plane(1), nullptr);
  EXPECT_EQ(rig.service.plane(1)->rank, 1);
  EXPECT_EQ(rig.service.plane(1)->plane_count, 2);
  EXPECT_EQ(rig.service.plane(1)->eval_id, 1u);
  EXPECT_EQ(rig.service.plane(2), nullptr);
  EXPECT_EQ(rig.events(EventId::EVAL_STARTED), 1u);
  EXPECT_EQ(rig.events(EventId::EVAL_COMPLETED), 1u);
  EXPECT_EQ(rig.events(EventId::FEWER_PLANES), 1u);  // 2 of 3
  EXPECT_EQ(rig.drain<tlm::GrindPlane>().size(), 2u);
}

TEST(EvaluationService, RefusesASecondStartWhileBusyAndDropsAnAbortedResult) {
  ServiceRig rig;
  rig.job.script = two_service_planes();
  rig.job.hold.store(true);
  rig.service.select(fsw::selection_from(roi_args(8, 4, 32, 24, 2)));
  ASSERT_TRUE(rig.service.start(rig.frame(), ::petra::arm::stow_pose()).ok());
  EXPECT_EQ(rig.service.poll(), fsw::EvalProgress::RUNNING);
  EXPECT_TRUE(rig.service.status().running);
  EXPECT_FALSE(
      rig.service.start(rig.frame(), ::petra::arm::stow_pose()).ok());  // the worker is busy

  rig.service.abort();
  EXPECT_EQ(rig.events(EventId::EVAL_ABORTED), 1u);
  EXPECT_TRUE(rig.unwind());  // its late result is dropped
  EXPECT_TRUE(rig.job.saw_cancel.load());
  EXPECT_EQ(rig.service.plane(0), nullptr);
  EXPECT_EQ(rig.events(EventId::EVAL_COMPLETED) + rig.events(EventId::EVAL_FAILED), 0u);
  EXPECT_TRUE(rig.drain<tlm::EvalResult>().empty());
}

TEST(EvaluationService, AFailedRunIsPublishedAsFailedWithItsStep) {
  ServiceRig rig;
  rig.job.fail = true;
  rig.service.select(fsw::selection_from(roi_args(8, 4, 32, 24, 2)));
  ASSERT_TRUE(rig.service.start(rig.frame(), ::petra::arm::stow_pose()).ok());
  EXPECT_EQ(rig.settle(), fsw::EvalProgress::FAILED);
  EXPECT_EQ(rig.events(EventId::EVAL_FAILED), 1u);
  const auto results = rig.drain<tlm::EvalResult>();
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].status, 2);
  EXPECT_EQ(rig.service.plane(0), nullptr);
}

}  // namespace
}  // namespace petra::test
