// TEST DOUBLE. A PipelineJob that computes nothing: it returns the planes a
// test scripted, so executive tests can check plumbing (commands, worker
// thread, telemetry) without the image pipeline. Never linked into petra-fsw.
#pragma once

#include <atomic>
#include <cstring>

#include "fsw/pipeline_job.hpp"

namespace petra::test {

class ScriptedPipelineJob final : public fsw::PipelineJob {
 public:
  // What the next runs return.
  fsw::EvalOutput script;
  bool fail = false;
  // When set, run() waits (polling cancel) until release() — a long evaluation.
  std::atomic<bool> hold{false};
  std::atomic<int> runs{0};
  std::atomic<bool> saw_cancel{false};
  // While held, keep running after a cancel (an abort still unwinding: BUSY).
  std::atomic<bool> ignore_cancel{false};
  fsw::EvalRequest last_request;
  // PROPOSE: the list the next proposal runs return (hand-built by the test).
  ProposalList proposals;
  bool proposes = true;       // can_propose()
  fsw::JobLimits job_limits;  // limits() (0: none)

  bool can_propose() const override { return proposes; }
  fsw::JobLimits limits() const override { return job_limits; }

  void release() { hold.store(false); }

  const char* name() const override { return "scripted test double"; }
  std::size_t arena_bytes(const fsw::JobBudget& b) const override {
    return static_cast<std::size_t>(b.max_width) * static_cast<std::size_t>(b.max_height) * 4 +
           4096;
  }
  Status run(const fsw::EvalRequest& request, Arena& arena, const std::atomic<bool>& cancel,
             fsw::EvalOutput& out) override {
    last_request = request;
    runs.fetch_add(1);
    while (hold.load()) {
      if (cancel.load() && !ignore_cancel.load()) {
        saw_cancel.store(true);
        return Error::make(Errc::not_ready, "cancelled");
      }
      struct timespec ts {
        0, 1000000
      };
      nanosleep(&ts, nullptr);
    }
    if (fail) {
      out.failed_step = fsw::Step::MATCH;
      return Error::make(Errc::no_solution, "scripted failure");
    }
    if (request.kind == fsw::JobKind::PROPOSE) {
      out.proposals = &proposals;
      return {};
    }
    out = script;
    // A disparity "product": the ROI of the left image, copied through the arena.
    auto pixels =
        arena.allocate<std::uint8_t>(static_cast<std::size_t>(request.selection.roi.w) *
                                         static_cast<std::size_t>(request.selection.roi.h),
                                     "disp");
    if (!pixels) return pixels.error();
    auto view = Gray8View::over(*pixels, request.selection.roi.w, request.selection.roi.h);
    copy_pixels<std::uint8_t, std::uint8_t>(request.left.sub(request.selection.roi), view);
    out.disparity_gray = view;
    for (std::size_t i = 0; i < out.step_us.size(); ++i)
      out.step_us[i] = static_cast<std::uint32_t>(10 * (i + 1));
    return {};
  }
};

}  // namespace petra::test
