// PipelineRunner: runs a PipelineJob on one worker thread created at init
// with a fixed stack, so the loop keeps servicing commands and housekeeping
// during a long evaluation. The loop starts a run, polls for its end, and may
// cancel it; the worker beats the WORKER heartbeat while it waits for work.
#pragma once

#include <pthread.h>

#include <atomic>
#include <cstddef>

#include "algo/core/arena.hpp"
#include "fsw/health.hpp"
#include "fsw/pipeline_job.hpp"
#include "hal/clock.hpp"

namespace petra::fsw {

class PipelineRunner {
 public:
  PipelineRunner() = default;
  ~PipelineRunner();
  PipelineRunner(const PipelineRunner&) = delete;
  PipelineRunner& operator=(const PipelineRunner&) = delete;

  // job may be nullptr (no pipeline in this build: start() then refuses).
  // Calls job->init(budget, rig, arena) once; every run then starts from the
  // arena as init left it.
  Status init(PipelineJob* job, std::span<std::byte> arena_memory, const JobBudget& budget,
              const StereoRig* rig, std::size_t stack_bytes, Health* health,
              const hal::Clock* clock);
  void shutdown();

  bool has_job() const { return job_ != nullptr; }
  bool busy() const { return state_.load(std::memory_order_acquire) != kIdle; }
  // Starts a run; the request's views must stay valid until it ends.
  Status start(const EvalRequest& request);
  void cancel() { cancel_.store(true, std::memory_order_relaxed); }
  bool cancelled() const { return cancel_.load(std::memory_order_relaxed); }
  // True once per finished run; then status() and output() describe it
  // (output valid until the next start).
  bool poll_done();
  const Status& status() const { return status_; }
  const EvalOutput& output() const { return output_; }
  std::size_t arena_capacity() const { return arena_.capacity(); }
  std::size_t arena_high_water() const { return high_water_.load(std::memory_order_relaxed); }

 private:
  enum : int { kIdle = 0, kQueued = 1, kRunning = 2, kDone = 3 };
  static void* thread_main(void* self);
  void worker_loop();

  PipelineJob* job_ = nullptr;
  Health* health_ = nullptr;
  const hal::Clock* clock_ = nullptr;
  Arena arena_;
  std::size_t run_mark_ = 0;  // arena position after job->init()
  EvalRequest request_;
  EvalOutput output_;
  Status status_;
  std::atomic<int> state_{kIdle};
  std::atomic<bool> cancel_{false};
  std::atomic<bool> stop_{false};
  std::atomic<std::size_t> high_water_{0};
  pthread_t thread_{};
  bool thread_started_ = false;
  pthread_mutex_t mutex_ = PTHREAD_MUTEX_INITIALIZER;
  pthread_cond_t wake_ = PTHREAD_COND_INITIALIZER;
};

}  // namespace petra::fsw
