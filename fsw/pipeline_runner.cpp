#include "fsw/pipeline_runner.hpp"

#include <ctime>

namespace petra::fsw {

PipelineRunner::~PipelineRunner() {
  shutdown();
}

Status PipelineRunner::init(PipelineJob* job, std::span<std::byte> arena_memory,
                            const JobBudget& budget, const StereoRig* rig, std::size_t stack_bytes,
                            Health* health, const hal::Clock* clock) {
  job_ = job;
  health_ = health;
  clock_ = clock;
  arena_ = Arena(arena_memory);
  if (job_ != nullptr) {
    const Status s = job_->init(budget, rig, arena_);
    if (!s) return Error::make(s.code(), "pipeline '%s' init: %s", job_->name(), s.error().message);
  }
  run_mark_ = arena_.mark();
  high_water_.store(arena_.high_water());
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  const int rs = pthread_attr_setstacksize(&attr, stack_bytes);
  const int rc = rs == 0 ? pthread_create(&thread_, &attr, &PipelineRunner::thread_main, this) : rs;
  pthread_attr_destroy(&attr);
  if (rc != 0)
    return Error::make(Errc::io_error, "pipeline worker: cannot start with a %zu-byte stack (%d)",
                       stack_bytes, rc);
  thread_started_ = true;
  return {};
}

void PipelineRunner::shutdown() {
  if (!thread_started_) return;
  cancel_.store(true);
  pthread_mutex_lock(&mutex_);
  stop_.store(true);
  pthread_cond_signal(&wake_);
  pthread_mutex_unlock(&mutex_);
  pthread_join(thread_, nullptr);
  thread_started_ = false;
}

Status PipelineRunner::start(const EvalRequest& request) {
  if (job_ == nullptr) return Error::make(Errc::not_ready, "no pipeline in this build");
  if (busy()) return Error::make(Errc::not_ready, "pipeline worker busy");
  pthread_mutex_lock(&mutex_);
  request_ = request;
  output_ = EvalOutput{};
  status_ = Status{};
  cancel_.store(false);
  state_.store(kQueued, std::memory_order_release);
  pthread_cond_signal(&wake_);
  pthread_mutex_unlock(&mutex_);
  return {};
}

bool PipelineRunner::poll_done() {
  if (state_.load(std::memory_order_acquire) != kDone) return false;
  state_.store(kIdle, std::memory_order_release);
  return true;
}

void* PipelineRunner::thread_main(void* self) {
  static_cast<PipelineRunner*>(self)->worker_loop();
  return nullptr;
}

void PipelineRunner::worker_loop() {
  pthread_mutex_lock(&mutex_);
  while (!stop_.load()) {
    if (state_.load(std::memory_order_acquire) != kQueued) {
      // Wake at least every 100 ms to beat the heartbeat while idle.
      timespec deadline{};
      clock_gettime(CLOCK_REALTIME, &deadline);
      deadline.tv_nsec += 100000000L;
      if (deadline.tv_nsec >= 1000000000L) {
        deadline.tv_sec += 1;
        deadline.tv_nsec -= 1000000000L;
      }
      pthread_cond_timedwait(&wake_, &mutex_, &deadline);
      health_->beat(Component::WORKER, clock_->monotonic_ns());
      continue;
    }
    state_.store(kRunning, std::memory_order_release);
    pthread_mutex_unlock(&mutex_);
    health_->set_exempt(Component::WORKER, true, clock_->monotonic_ns());

    arena_.release_to(run_mark_);  // keeps what job->init() took
    const Status s = job_->run(request_, arena_, cancel_, output_);
    if (arena_.high_water() > high_water_.load()) high_water_.store(arena_.high_water());

    health_->set_exempt(Component::WORKER, false, clock_->monotonic_ns());
    pthread_mutex_lock(&mutex_);
    status_ = s;
    state_.store(kDone, std::memory_order_release);
  }
  pthread_mutex_unlock(&mutex_);
}

}  // namespace petra::fsw
