// Per-step timing without OS calls: the caller (fsw executive, ground CLI,
// benchmark) supplies a monotonic clock as a plain function pointer; algo/
// only subtracts readings. A null clock records zeros.
#pragma once

#include <cstddef>
#include <cstdint>

#include "algo/core/pipeline_steps.hpp"
#include "algo/core/result.hpp"

namespace petra {

struct StepClock {
  std::uint64_t (*now_ns)(void* context) = nullptr;
  void* context = nullptr;
  // Optional: told when a step starts (running) and ends, so a caller can
  // report progress of long steps, or where a failure happened.
  void (*on_step)(void* context, PipelineStep step, bool running) = nullptr;
  // Optional: asked between steps; true ends the run with Errc::cancelled, so
  // an operator's ABORT stops a long evaluation at the next step boundary.
  bool (*cancel_requested)(void* context) = nullptr;
  std::uint64_t read() const { return now_ns ? now_ns(context) : 0; }
  bool cancelled() const { return cancel_requested != nullptr && cancel_requested(context); }
  void step(PipelineStep step, bool running) const {
    if (on_step) on_step(context, step, running);
  }
};

struct StepTiming {
  PipelineStep step = PipelineStep::rectify;
  const char* name = "";  // step_name(step)
  std::uint64_t ns = 0;
};

// A fixed table of step timings, filled in the order the steps run.
struct StepTimings {
  static constexpr std::size_t kCapacity = 16;
  StepTiming steps[kCapacity];
  std::size_t count = 0;

  void add(PipelineStep step, std::uint64_t ns) {
    if (count < kCapacity) steps[count++] = {step, step_name(step), ns};
  }
  std::uint64_t total_ns() const {
    std::uint64_t t = 0;
    for (std::size_t i = 0; i < count; ++i) t += steps[i].ns;
    return t;
  }
};

// Call before each step: an error once the caller asked to stop.
inline Status checkpoint(const StepClock& clock, PipelineStep next_step) {
  if (clock.cancelled())
    return Error::make(Errc::cancelled, "cancelled before %s", step_name(next_step));
  return {};
}

// Times the region between construction and stop() (or destruction).
class StepTimer {
 public:
  StepTimer(const StepClock& clock, StepTimings& timings, PipelineStep step)
      : clock_(clock), timings_(timings), step_(step), start_(clock.read()) {
    clock_.step(step_, true);
  }
  ~StepTimer() { stop(); }
  StepTimer(const StepTimer&) = delete;
  StepTimer& operator=(const StepTimer&) = delete;
  void stop() {
    if (stopped_) return;
    stopped_ = true;
    timings_.add(step_, clock_.read() - start_);
    clock_.step(step_, false);
  }

 private:
  const StepClock& clock_;
  StepTimings& timings_;
  PipelineStep step_;
  std::uint64_t start_;
  bool stopped_ = false;
};

}  // namespace petra
