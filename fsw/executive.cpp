#include "fsw/executive.hpp"

#include <sys/mman.h>
#include <time.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>

#include "algo/camera/calib_json.hpp"
#include "fsw/arm_geometry.hpp"
#include "hal/file_io.hpp"

namespace petra::fsw {

namespace {
constexpr std::size_t kQueueReserve = 16;  // slots products leave free for events and HK
constexpr std::size_t kRxSlotBytes = cmd::kMaxCommandBytes + 1;

std::size_t align_up(std::size_t n) {
  return (n + 63) / 64 * 64;
}
}  // namespace

Executive::~Executive() {
  shutdown();
}

void Executive::shutdown() {
  if (initialised_) watchdog_.disarm();  // a deliberate stop is not a hang
  evaluation_.shutdown();
  uplink_.close();
  downlink_.close();
}

tlm::TmTime Executive::now_tm() const {
  return tm_time(deps_.clock->realtime_ns());
}

Status Executive::allocate(const FswConfig& config, const JobBudget& pb, std::size_t arena_bytes) {
  const Budget& b = config.budget;
  const auto frame =
      static_cast<std::size_t>(b.image_width) * static_cast<std::size_t>(b.image_height);
  const auto product_sizes =
      ProductStreamer::bytes_needed(b.image_width, b.image_height, b.cloud_points);
  const std::size_t queue_bytes = tlm::TlmQueue::bytes_for(b.tlm_queue_packets);
  // One slot per datagram of a cycle's drain; one byte more: oversize shows as TOO_LONG.
  const std::size_t rx_bytes = config.commands_per_cycle * kRxSlotBytes;
  const std::size_t rx_sizes_bytes = config.commands_per_cycle * sizeof(std::size_t);
  std::size_t total = 2 * align_up(frame) + align_up(queue_bytes) +
                      align_up(b.tlm_queue_packets * sizeof(std::uint16_t)) + align_up(rx_bytes) +
                      align_up(rx_sizes_bytes) + align_up(arena_bytes);
  for (std::size_t s : product_sizes) total += align_up(s);
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  const std::size_t machine =
      pages > 0 && page > 0 ? static_cast<std::size_t>(pages) * static_cast<std::size_t>(page) : 0;
  if (machine != 0 && total > machine)
    return Error::make(Errc::capacity_exceeded,
                       "init: the budget asks for %zu bytes, the machine has %zu (budget.arena_mb, "
                       "budget.roi_width/roi_height)",
                       total, machine);

  // The one allocation, at init; nothrow, so a failure is an error value.
  memory_.reset(new (std::nothrow) std::byte[total]);  // NOLINT(cppcoreguidelines-owning-memory)
  if (!memory_)
    return Error::make(Errc::capacity_exceeded, "init: cannot allocate %zu bytes", total);
  std::memset(memory_.get(), 0, total);  // touch every page now: resident memory stays flat
  memory_bytes_ = total;

  std::size_t at = 0;
  auto take = [&](std::size_t n) {
    std::byte* p = memory_.get() + at;
    at += align_up(n);
    return p;
  };
  left_ = Gray8View(reinterpret_cast<std::uint8_t*>(take(frame)), deps_.camera->width(),
                    deps_.camera->height());
  right_ = Gray8View(reinterpret_cast<std::uint8_t*>(take(frame)), deps_.camera->width(),
                     deps_.camera->height());
  auto* queue_mem = reinterpret_cast<std::uint8_t*>(take(queue_bytes));
  auto* lengths =
      reinterpret_cast<std::uint16_t*>(take(b.tlm_queue_packets * sizeof(std::uint16_t)));
  queue_.init({queue_mem, queue_bytes}, {lengths, b.tlm_queue_packets});
  rx_ = {reinterpret_cast<std::uint8_t*>(take(rx_bytes)), rx_bytes};
  rx_sizes_ = {reinterpret_cast<std::size_t*>(take(rx_sizes_bytes)), config.commands_per_cycle};
  std::array<std::span<std::uint8_t>, kProductKinds> product_mem{};
  for (std::size_t k = 0; k < kProductKinds; ++k)
    product_mem[k] = {reinterpret_cast<std::uint8_t*>(take(product_sizes[k])), product_sizes[k]};
  products_.init(product_mem, &events_);
  std::byte* arena = take(arena_bytes);
  PETRA_ASSERT(at <= total);
  EvaluationWiring w;
  w.job = deps_.job;
  w.arena = {arena, arena_bytes};
  w.budget = pb;
  w.rig = has_rig_ ? &rig_ : nullptr;
  w.worker_stack_bytes = b.worker_stack_bytes;
  w.health = &health_;
  w.clock = deps_.clock;
  w.params = &params_;
  w.events = &events_;
  w.queue = &queue_;
  w.products = &products_;
  return evaluation_.init(w);
}

// The replay guard cannot be left out: the counter is always kept (beside the
// key unless the configuration names a file), and a missing or unreadable file
// stops the start until the operator gives a floor (docs/ops.md "Counter").
Status Executive::open_counter() {
  const FswConfig& c = config_;
  char path[cmd::CounterStore::kPathBytes];
  if (c.counter_file[0] != '\0')
    (void)std::snprintf(path, sizeof(path), "%s", c.counter_file.data());
  else
    (void)std::snprintf(path, sizeof(path), "%s.fsw-counter", c.key_file.data());
  PETRA_TRY(counter_store_.bind(path, cmd::key_id(key_)));
  auto stored = counter_store_.load();
  const bool usable = stored.ok() && stored->exists;
  if (!usable && c.counter_floor < 0) {
    (void)std::fprintf(stderr,
                       "petra-fsw: counter file %s %s: a command accepted before could be "
                       "replayed, so petra-fsw does not start. If the key is new, or you know "
                       "the last counter the ground sent (N), start once with --counter-floor N "
                       "(docs/ops.md \"Command counter\").\n",
                       path, stored.ok() ? "is missing" : stored.error().message);
    return Error::make(Errc::missing_field, "uplink counter %s: start with --counter-floor N",
                       stored.ok() ? "file missing" : "file unreadable");
  }
  std::uint32_t last = usable ? stored->counter : 0;
  if (usable && !stored->same_key) {  // re-keyed: the old key's commands no longer verify
    previous_key_counter_ = stored->counter;
    last = 0;
  }
  if (c.counter_floor > static_cast<std::int64_t>(last))
    last = static_cast<std::uint32_t>(c.counter_floor);
  if (last == 0xFFFFFFFFu)
    (void)std::fprintf(stderr,
                       "petra-fsw: the uplink key's counter is exhausted (4294967295): every "
                       "command is a REPLAY until a new key (petra keygen, docs/ops.md)\n");
  cmd_.last_counter = last;
  // Written now: the file exists, is this key's, and the folder is writable.
  return counter_store_.store(last);
}

void Executive::store_counter(std::uint32_t counter) {
  if (!counter_store_.is_bound()) return;
  const Status s = counter_store_.store(counter);
  if (!s && !counter_store_failed_) {
    counter_store_failed_ = true;  // one event, not one per command
    events_.raise(EventId::COUNTER_STORE_FAILED, static_cast<std::int32_t>(s.code()));
  }
}

Status Executive::init(const FswConfig& config, const Dependencies& deps) {
  if (deps.camera == nullptr || deps.clock == nullptr)
    return Error::make(Errc::invalid_argument, "init: a camera and a clock are required");
  config_ = config;
  deps_ = deps;
  boot_ns_ = deps.clock->monotonic_ns();
  const Budget& b = config.budget;
  if (deps.camera->width() > b.image_width || deps.camera->height() > b.image_height)
    return Error::make(Errc::capacity_exceeded,
                       "init: camera frames %dx%d exceed budget.image_width/height %dx%d",
                       deps.camera->width(), deps.camera->height(), b.image_width, b.image_height);

  PETRA_TRY(cmd::auth_init());
  auto key = cmd::load_key_file(config.key_file.data());
  if (!key) return key.error();
  key_ = *key;
  PETRA_TRY(open_counter());

  int params_loaded = 0;
  if (config.param_file[0] != '\0') {
    auto text = std::make_unique<char[]>(65536);  // init only
    auto n = hal::read_small_file(config.param_file.data(), {text.get(), 65536});
    if (!n) return n.error();
    auto loaded = params_.load_defaults(text.get(), *n);
    if (!loaded)
      return Error::make(loaded.code(), "%s: %s", config.param_file.data(), loaded.error().message);
    params_loaded = *loaded;
  }
  if (config.calib_file[0] != '\0') {
    auto text = std::make_unique<char[]>(65536);
    auto n = hal::read_small_file(config.calib_file.data(), {text.get(), 65536});
    if (!n) return n.error();
    auto rig = parse_calib_json(std::string_view(text.get(), *n));
    if (!rig)
      return Error::make(rig.code(), "%s: %s", config.calib_file.data(), rig.error().message);
    rig_ = *rig;
    has_rig_ = true;
  }

  JobBudget pb{b.image_width, b.image_height, b.cloud_points, b.arena_bytes};
  pb.max_roi_width = b.roi_width;
  pb.max_roi_height = b.roi_height;
  pb.rig = has_rig_ ? &rig_ : nullptr;
  pb.arm_geometry = arm_geometry(config);
  // The arena is what the job needs for the budget, or budget.arena_mb when given.
  const std::size_t need = deps.job != nullptr ? deps.job->arena_bytes(pb) : 0;
  if (b.arena_bytes != 0 && need > b.arena_bytes)
    return Error::make(Errc::capacity_exceeded,
                       "init: pipeline '%s' needs %zu arena bytes for its ROI budget "
                       "(budget.roi_width/roi_height), budget.arena_mb gives %zu",
                       deps.job->name(), need, b.arena_bytes);
  const std::size_t arena_bytes = b.arena_bytes != 0 ? b.arena_bytes : need;
  PETRA_TRY(allocate(config, pb, deps.job != nullptr ? arena_bytes : 0));

  PETRA_TRY(uplink_.open(config.cmd_host.data(), config.cmd_port));
  uplink_.set_receive_buffer(1 << 18);  // a burst of commands waits for the next cycles
  PETRA_TRY(downlink_.open("0.0.0.0", 0));
  PETRA_TRY(downlink_.set_peer(config.tlm_host.data(), config.tlm_port));
  downlink_.set_send_buffer(1 << 20);

  if (config.watchdog_device[0] != '\0') PETRA_TRY(watchdog_.open(config.watchdog_device.data()));
  events_.init(&queue_, deps.clock);
  modes_.init(&events_);
  health_.reset(deps.clock->monotonic_ns());
  update_periods();
  if (config.lock_memory && ::mlockall(MCL_CURRENT | MCL_FUTURE) != 0)
    (void)std::fprintf(stderr, "petra-fsw: mlockall refused; memory not locked\n");

  events_.raise(EventId::BOOT_COMPLETE, static_cast<std::int32_t>(memory_bytes_),
                static_cast<std::int32_t>(evaluation_.status().arena_bytes), params_loaded);
  if (previous_key_counter_ >= 0)
    events_.raise(EventId::UPLINK_NEW_KEY, static_cast<std::int32_t>(previous_key_counter_));
  modes_.request(Mode::IDLE, 0);
  initialised_ = true;
  return {};
}

void Executive::update_periods() {
  const std::uint32_t cycle = config_.cycle_ms;
  const auto hk = static_cast<std::uint32_t>(params_.get_int(ParamId::HK_PERIOD_MS)) / cycle;
  const std::uint32_t health = config_.health_period_ms / cycle;
  groups_ = {{{Component::UPLINK, &Executive::service_uplink, 1},
              {Component::PIPELINE, &Executive::poll_pipeline, 1},
              {Component::ARM, &Executive::poll_arm, 1},
              {Component::PRODUCTS, &Executive::pump_products, 1},
              {Component::HOUSEKEEPING, &Executive::send_housekeeping, hk > 0 ? hk : 1},
              {Component::WORKER, &Executive::check_health, health > 0 ? health : 1},
              {Component::DOWNLINK, &Executive::flush_downlink, 1}}};
  const std::int64_t base = params_.get_int(ParamId::HEARTBEAT_TIMEOUT_MS) * hal::kNsPerMs;
  for (const RateGroup& g : groups_)
    heartbeat_timeout_ns_[static_cast<std::size_t>(g.component)] =
        base + static_cast<std::int64_t>(g.period_cycles * cycle) * hal::kNsPerMs;
  // The worker beats every 100 ms from its own thread.
  heartbeat_timeout_ns_[static_cast<std::size_t>(Component::WORKER)] = base;
}

void Executive::run_cycle() {
  const std::int64_t start = deps_.clock->monotonic_ns();
  for (const RateGroup& g : groups_) {
    if (loop_.cycles % g.period_cycles != 0) continue;
    (this->*g.run)();
    // check_health is listed under WORKER only to give it a slot; the worker beats itself.
    if (g.component != Component::WORKER) health_.beat(g.component, deps_.clock->monotonic_ns());
  }
  ++loop_.cycles;
  watchdog_.kick();  // the loop came round: a hung loop stops kicking
  const std::int64_t end = deps_.clock->monotonic_ns();
  const auto us = static_cast<std::uint32_t>((end - start) / 1000);
  if (us > loop_.max_cycle_us) loop_.max_cycle_us = us;
  if (us > config_.cycle_ms * 1000) {
    ++loop_.overruns;
    if (end - last_overrun_event_ns_ > 1000 * hal::kNsPerMs) {  // at most one event a second
      last_overrun_event_ns_ = end;
      events_.raise(EventId::CYCLE_OVERRUN, static_cast<std::int32_t>(us),
                    static_cast<std::int32_t>(config_.cycle_ms * 1000));
    }
  }
}

void Executive::run(const volatile std::sig_atomic_t* stop) {
  const std::int64_t period = static_cast<std::int64_t>(config_.cycle_ms) * hal::kNsPerMs;
  timespec next{};
  clock_gettime(CLOCK_MONOTONIC, &next);
  while (*stop == 0) {
    run_cycle();
    next.tv_nsec += period;
    while (next.tv_nsec >= 1000000000L) {
      next.tv_nsec -= 1000000000L;
      next.tv_sec += 1;
    }
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    if (now.tv_sec > next.tv_sec || (now.tv_sec == next.tv_sec && now.tv_nsec > next.tv_nsec))
      next = now;  // overran: start the next frame now, do not try to catch up
    else
      clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
  }
}

void Executive::service_uplink() {
  // Bounded: what is left waits in the socket for the next cycles. An empty or
  // short datagram is one more bad packet (TOO_SHORT), never the end of the drain.
  std::uint32_t count = 0;
  for (; count < config_.commands_per_cycle; ++count) {
    const std::span<std::uint8_t> slot = rx_.subspan(count * kRxSlotBytes, kRxSlotBytes);
    auto n = uplink_.receive(slot);
    if (!n || !n->got) break;
    rx_sizes_[count] = n->size < slot.size() ? n->size : slot.size();
  }
  if (count > 0) reserve_counters(count);
  for (std::uint32_t i = 0; i < count; ++i)
    handle_datagram(rx_.subspan(i * kRxSlotBytes, rx_sizes_[i]));
  report_uplink_losses();
}

// Before any of the cycle's commands runs, the counter the last authentic one
// will leave is made durable: one store (two fsyncs) per cycle, not per
// command. A power cut before the cycle ends loses the cycle's commands that
// did not run yet (their counters are used up), never lets one run twice.
void Executive::reserve_counters(std::uint32_t count) {
  cmd::ValidationContext ctx = validation_context();
  for (std::uint32_t i = 0; i < count; ++i) {
    const cmd::Verdict v = cmd::validate_command(rx_.subspan(i * kRxSlotBytes, rx_sizes_[i]), ctx);
    if (v.authenticated) ctx.last_counter = v.command.counter;  // as handle_datagram will
  }
  if (ctx.last_counter != cmd_.last_counter) store_counter(ctx.last_counter);
}

void Executive::report_uplink_losses() {
  cmd_.kernel_drops = uplink_.kernel_drops() - kernel_drops_base_;
  const bool ended =
      throttle_.end_window(deps_.clock->monotonic_ns(), [this](Reason r, std::uint32_t n) {
        events_.raise(EventId::CMD_REJECTS_UNREPORTED, static_cast<std::int32_t>(r),
                      static_cast<std::int32_t>(n), RejectionThrottle::kWindowMs);
      });
  if (ended && cmd_.kernel_drops != reported_kernel_drops_) {  // at most one event a window
    reported_kernel_drops_ = cmd_.kernel_drops;
    events_.raise(EventId::CMD_KERNEL_DROPS, static_cast<std::int32_t>(cmd_.kernel_drops));
  }
}

void Executive::poll_arm() {
  // E-stop: the rising edge stops the arm and enters SAFE; an unreadable line counts as asserted.
  if (deps_.estop != nullptr) {
    auto line = deps_.estop->read();
    const bool asserted = !line.ok() || *line;
    if (asserted && !estop_latched_) {
      if (deps_.arm != nullptr) deps_.arm->quick_stop();
      events_.raise(EventId::ESTOP_ASSERTED);
      ++loop_.faults;
      enter_safe();
    }
    estop_latched_ = asserted;
  }
  if (deps_.arm == nullptr) return;
  // Every cycle, moving or not: the arm's drives need their bus serviced.
  const ArmProgress p = deps_.arm->poll();
  ArmEventOut e;
  bool safe = false;
  while (deps_.arm->pop_event(e)) {  // bounded by the arm's event queue
    events_.raise(e.id, e.args[0], e.args[1], e.args[2], e.args[3]);
    safe = safe || e.safe;
  }
  if (safe && modes_.mode() != Mode::SAFE) {
    ++loop_.faults;
    enter_safe();  // fails a running arm command (ABORTED) and stops the drives
    return;
  }
  if (!pending_arm_.active || p == ArmProgress::MOVING) return;
  if (p == ArmProgress::REACHED)
    complete(pending_arm_.function_code, pending_arm_.counter);
  else
    fail(pending_arm_.function_code, pending_arm_.counter, Reason::ARM_FAILED);
  pending_arm_.active = false;
  if (modes_.mode() == Mode::ARM_MOVING) modes_.request(Mode::IDLE, 0);
}

void Executive::pump_products() {
  products_.pump(queue_, now_tm(),
                 static_cast<std::size_t>(params_.get_int(ParamId::PRODUCT_CHUNKS_PER_CYCLE)),
                 kQueueReserve);
}

void Executive::send_housekeeping() {
  tlm::Housekeeping hk;
  hk.mode = static_cast<std::uint8_t>(modes_.mode());
  hk.uptime_s =
      static_cast<std::uint32_t>((deps_.clock->monotonic_ns() - boot_ns_) / (1000 * hal::kNsPerMs));
  hk.cycles = loop_.cycles;
  hk.cycle_overruns = loop_.overruns;
  hk.max_cycle_us = loop_.max_cycle_us;
  hk.cmd_received = cmd_.received;
  hk.cmd_accepted = cmd_.accepted;
  hk.cmd_rejected = cmd_.rejected;
  hk.cmd_completed = cmd_.completed;
  hk.cmd_failed = cmd_.failed;
  hk.last_counter = cmd_.last_counter;
  hk.last_function_code = cmd_.last_function_code;
  hk.last_reason = static_cast<std::uint8_t>(cmd_.last_reason);
  hk.cmd_unreported = cmd_.unreported;
  hk.cmd_kernel_drops = cmd_.kernel_drops;
  hk.tlm_sent = loop_.tlm_sent;
  hk.tlm_dropped = queue_.dropped();
  hk.tlm_send_errors = loop_.tlm_send_errors;
  hk.tlm_queue_high_water = static_cast<std::uint16_t>(queue_.high_water());
  hk.events = events_.total();
  hk.faults = loop_.faults;
  hk.memory_bytes = static_cast<std::uint32_t>(memory_bytes_);
  const EvalStatus eval = evaluation_.status();
  hk.arena_bytes = static_cast<std::uint32_t>(eval.arena_bytes);
  hk.arena_high_water_bytes = static_cast<std::uint32_t>(eval.arena_high_water_bytes);
  hk.frames = loop_.frames;
  hk.evaluations = loop_.evaluations;
  hk.eval_running = eval.running ? 1 : 0;
  hk.eval_elapsed_ms = eval.elapsed_ms;
  hk.step_us = eval.step_us;
  queue_.push(hk, now_tm());
  tlm::ArmStatus arm;
  if (deps_.arm != nullptr && deps_.arm->status(arm)) queue_.push(arm, now_tm());
}

void Executive::check_health() {
  const std::int64_t now = deps_.clock->monotonic_ns();
  std::int64_t silent = 0;
  const int late = health_.check(now, heartbeat_timeout_ns_, silent);
  if (late < 0) return;
  ++loop_.faults;
  events_.raise(EventId::HEARTBEAT_LOST, late, static_cast<std::int32_t>(silent / hal::kNsPerMs));
  enter_safe();
}

void Executive::flush_downlink() {
  while (!queue_.empty()) {  // bounded by the queue capacity
    const hal::SendResult r = downlink_.send(queue_.front());
    if (r == hal::SendResult::would_block) break;  // never block: try again next cycle
    if (r == hal::SendResult::sent)
      ++loop_.tlm_sent;
    else
      ++loop_.tlm_send_errors;
    queue_.pop();
  }
  if (queue_.dropped() != reported_drops_ && queue_.free_slots() > kQueueReserve) {
    reported_drops_ = queue_.dropped();
    events_.raise(EventId::TLM_DROPPED, static_cast<std::int32_t>(reported_drops_));
  }
}

}  // namespace petra::fsw
