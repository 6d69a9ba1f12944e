#include "hal/libcamera_capture.hpp"

#include <cstdio>
#include <cstring>

#if PETRA_HAVE_LIBCAMERA
#include <sys/mman.h>

#include <libcamera/libcamera.h>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <vector>

#include "hal/errno_text.hpp"
#endif

namespace petra::hal {

#if PETRA_HAVE_LIBCAMERA

namespace lc = libcamera;

namespace {

// libcamera allows one CameraManager per process: shared by every capture.
// Once a camera is abandoned (LibcameraCapture::abandon) the manager is never
// stopped or destroyed: it still runs that camera.
struct SharedManager {
  std::mutex mutex;
  std::unique_ptr<lc::CameraManager> manager;
  int users = 0;
  bool abandoned = false;
  ~SharedManager() {
    if (abandoned) (void)manager.release();
  }
};
SharedManager& shared_manager() {
  static SharedManager m;
  return m;
}

lc::PixelFormat to_libcamera(PixelFormat f) {
  switch (f) {
    case PixelFormat::grey:
      return lc::formats::R8;
    case PixelFormat::yuyv:
      return lc::formats::YUYV;
    case PixelFormat::rgb24:  // memory R, G, B = libcamera (DRM) BGR888
      return lc::formats::BGR888;
    case PixelFormat::bgr24:
      return lc::formats::RGB888;
    case PixelFormat::y16:
      break;  // no 16-bit gray in libcamera 0.0.3
  }
  return lc::PixelFormat();
}

}  // namespace

struct LibcameraCapture::Impl {
  bool manager = false;
  std::shared_ptr<lc::Camera> camera;
  bool acquired = false;
  bool started = false;
  std::unique_ptr<lc::CameraConfiguration> config;
  lc::Stream* stream = nullptr;
  std::unique_ptr<lc::FrameBufferAllocator> allocator;
  std::vector<std::unique_ptr<lc::Request>> requests;  // one per buffer, made in open()
  std::array<std::uint8_t*, kMaxBuffers> map{};
  std::array<std::size_t, kMaxBuffers> map_length{};
  std::array<const std::uint8_t*, kMaxBuffers> data{};

  // Completed requests, filled by libcamera's thread.
  std::mutex mutex;
  std::condition_variable completed;
  std::array<lc::Request*, kMaxBuffers> done{};
  std::size_t head = 0;
  std::size_t count = 0;
  lc::Request* held = nullptr;
  FrameChecker checker;
  bool gaps_are_faults = true;
  // What tells a camera that can no longer be stopped (stop() below).
  int in_flight = 0;          // requests libcamera holds, not yet completed
  bool stalled = false;       // a wait ran out with requests in flight, none came since
  bool disconnected = false;  // libcamera saw the device go
  bool abandoned = false;

  void on_complete(lc::Request* r) {
    {
      std::lock_guard lock(mutex);
      if (count < done.size()) done[(head + count++) % done.size()] = r;
      if (in_flight > 0) --in_flight;
      stalled = false;
    }
    completed.notify_one();
  }
  void on_disconnected() {
    std::lock_guard lock(mutex);
    disconnected = true;
  }
  lc::Request* pop(int timeout_ms) {
    std::unique_lock lock(mutex);
    completed.wait_for(lock, std::chrono::milliseconds(timeout_ms), [this] { return count > 0; });
    if (count == 0) {
      if (timeout_ms > 0 && in_flight > 0) stalled = true;
      return nullptr;
    }
    lc::Request* r = done[head];
    head = (head + 1) % done.size();
    --count;
    return r;
  }
  int queue(lc::Request* r) {
    {
      std::lock_guard lock(mutex);
      ++in_flight;  // before queueing: the completion may come first
    }
    const int rc = camera->queueRequest(r);
    if (rc < 0) {
      std::lock_guard lock(mutex);
      --in_flight;
    }
    return rc;
  }
  int requeue(lc::Request* r) {
    r->reuse(lc::Request::ReuseBuffers);
    return queue(r);
  }
  // The device is gone (or silent) while libcamera still holds requests of ours.
  bool lost() {
    std::lock_guard lock(mutex);
    return in_flight > 0 && (stalled || disconnected);
  }
};

bool libcamera_available() {
  return true;
}

LibcameraCapture::LibcameraCapture() = default;

LibcameraCapture::~LibcameraCapture() {
  close();
}

bool LibcameraCapture::is_open() const {
  return impl_ != nullptr && impl_->stream != nullptr;
}

Status LibcameraCapture::open(const LibcameraCaptureConfig& cfg) {
  close();
  if (cfg.width <= 0 || cfg.height <= 0 || cfg.width > 8192 || cfg.height > 8192)
    return Error::make(Errc::invalid_argument, "camera: size %dx%d outside 1..8192", cfg.width,
                       cfg.height);
  if (cfg.formats.empty())
    return Error::make(Errc::missing_field, "camera.formats: none configured");
  if (cfg.buffers < 2 || cfg.buffers > kMaxBuffers)
    return Error::make(Errc::invalid_argument, "camera.buffers: %d outside 2..%d", cfg.buffers,
                       kMaxBuffers);
  impl_ = std::make_unique<Impl>();
  impl_->gaps_are_faults = cfg.gaps_are_faults;
  PETRA_TRY(acquire_camera(cfg));
  PETRA_TRY(configure_stream(cfg));
  PETRA_TRY(map_requests());
  Impl& m = *impl_;
  m.camera->requestCompleted.connect(&m, &Impl::on_complete);
  m.camera->disconnected.connect(&m, &Impl::on_disconnected);
  m.checker.reset(format_, m.gaps_are_faults);
  return ok_status();
}

// The shared camera manager (started by its first user), the first camera
// whose id contains cfg.camera, acquired for this process.
Status LibcameraCapture::acquire_camera(const LibcameraCaptureConfig& cfg) {
  Impl& m = *impl_;
  {
    SharedManager& sm = shared_manager();
    std::lock_guard lock(sm.mutex);
    if (!sm.manager) {
      sm.manager = std::make_unique<lc::CameraManager>();
      if (const int r = sm.manager->start(); r < 0) {
        sm.manager.reset();
        impl_.reset();
        return Error::make(Errc::io_error, "libcamera: camera manager did not start (%s)",
                           errno_text(-r));
      }
    }
    ++sm.users;
    m.manager = true;
    for (const auto& c : sm.manager->cameras()) {
      if (cfg.camera[0] == '\0' || c->id().find(cfg.camera.data()) != std::string::npos) {
        m.camera = c;
        break;
      }
    }
  }
  if (!m.camera) {
    close();
    return Error::make(Errc::io_error, "libcamera: no camera matches '%s'", cfg.camera.data());
  }
  (void)std::snprintf(id_.data(), id_.size(), "%s", m.camera->id().c_str());
  if (m.camera->acquire() < 0) {
    close();
    return Error::make(Errc::io_error, "libcamera: camera '%s' is in use", id_.data());
  }
  m.acquired = true;
  return ok_status();
}

// One video stream in the first configured format the camera offers, at the
// configured size; format_ is what the camera gave.
Status LibcameraCapture::configure_stream(const LibcameraCaptureConfig& cfg) {
  Impl& m = *impl_;
  m.config = m.camera->generateConfiguration({lc::StreamRole::VideoRecording});
  if (!m.config || m.config->empty()) {
    close();
    return Error::make(Errc::io_error, "libcamera: '%s' has no video stream", id_.data());
  }
  lc::StreamConfiguration& sc = m.config->at(0);
  const auto offered = sc.formats().pixelformats();
  bool found = false;
  PixelFormat chosen = cfg.formats[0];
  for (PixelFormat want : cfg.formats) {
    const lc::PixelFormat lf = to_libcamera(want);
    for (const auto& o : offered) found = found || (lf.isValid() && o == lf);
    if (found) {
      chosen = want;
      break;
    }
  }
  if (!found) {
    close();
    return Error::make(Errc::wrong_type, "libcamera: '%s' offers none of the configured formats",
                       id_.data());
  }
  sc.pixelFormat = to_libcamera(chosen);
  sc.size = lc::Size(static_cast<unsigned>(cfg.width), static_cast<unsigned>(cfg.height));
  sc.bufferCount = static_cast<unsigned>(cfg.buffers);
  if (m.config->validate() == lc::CameraConfiguration::Invalid) {
    close();
    return Error::make(Errc::invalid_argument, "libcamera: '%s' refuses %dx%d %s", id_.data(),
                       cfg.width, cfg.height, pixel_format_name(chosen));
  }
  format_.pixel = chosen;
  format_.width = static_cast<int>(sc.size.width);
  format_.height = static_cast<int>(sc.size.height);
  format_.bytes_per_line = sc.stride;
  format_.image_bytes = sc.frameSize;
  format_.limited_range = chosen == PixelFormat::yuyv;  // Y'CbCr: video range by default
  if (sc.pixelFormat != to_libcamera(chosen)) {
    close();
    return Error::make(Errc::wrong_type, "libcamera: '%s' changed the format to %s", id_.data(),
                       sc.pixelFormat.toString().c_str());
  }
  if (auto s = check_negotiated(format_, chosen, cfg.width, cfg.height); !s) {
    close();
    return Error::make(s.error().code, "libcamera '%s': %s", id_.data(), s.error().message);
  }
  if (m.camera->configure(m.config.get()) < 0) {
    close();
    return Error::make(Errc::io_error, "libcamera: '%s' refused the configuration", id_.data());
  }
  m.stream = sc.stream();
  return ok_status();
}

// The stream's buffers, each mapped and in a request of its own.
Status LibcameraCapture::map_requests() {
  Impl& m = *impl_;
  m.allocator = std::make_unique<lc::FrameBufferAllocator>(m.camera);
  const int n = m.allocator->allocate(m.stream);
  if (n < 2 || n > kMaxBuffers) {
    close();
    return Error::make(Errc::capacity_exceeded, "libcamera: '%s' gave %d buffers, need 2..%d",
                       id_.data(), n, kMaxBuffers);
  }
  const auto& buffers = m.allocator->buffers(m.stream);
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    lc::FrameBuffer* fb = buffers[i].get();
    const auto& plane = fb->planes()[0];
    const std::size_t length = static_cast<std::size_t>(plane.offset) + plane.length;
    void* p = ::mmap(nullptr, length, PROT_READ, MAP_SHARED, plane.fd.get(), 0);
    if (p == MAP_FAILED) {
      close();
      return Error::make(Errc::io_error, "libcamera: mmap of buffer %zu failed", i);
    }
    m.map[i] = static_cast<std::uint8_t*>(p);
    m.map_length[i] = length;
    m.data[i] = m.map[i] + plane.offset;
    fb->setCookie(i);
    std::unique_ptr<lc::Request> req = m.camera->createRequest(i);
    if (!req || req->addBuffer(m.stream, fb) < 0) {
      close();
      return Error::make(Errc::io_error, "libcamera: cannot make request %zu", i);
    }
    m.requests.push_back(std::move(req));
  }
  return ok_status();
}

Status LibcameraCapture::start() {
  if (!is_open()) return Error::make(Errc::not_ready, "camera: start() before open()");
  Impl& m = *impl_;
  if (m.started) return ok_status();
  if (m.camera->start() < 0)
    return Error::make(Errc::io_error, "libcamera: '%s' did not start", id_.data());
  m.started = true;
  for (auto& r : m.requests)
    if (m.queue(r.get()) < 0)
      return Error::make(Errc::io_error, "libcamera: '%s' refused a request", id_.data());
  m.checker.reset(format_, m.gaps_are_faults);
  return ok_status();
}

// libcamera 0.0.3 cannot stop a camera whose device vanished while it held our
// requests: the pipeline's stop asserts they all came back, and the process
// aborts. Such a camera is left running (abandon()); the error says so.
Status LibcameraCapture::stop() {
  if (!is_open() || !impl_->started) return ok_status();
  Impl& m = *impl_;
  m.started = false;
  if (m.lost()) {
    m.abandoned = true;
    return Error::make(Errc::io_error,
                       "libcamera: '%s' lost with requests in flight: left unstopped", id_.data());
  }
  const int r = m.camera->stop();  // completes every queued request as cancelled
  std::lock_guard lock(m.mutex);
  m.count = 0;
  m.held = nullptr;
  if (r < 0) return Error::make(Errc::io_error, "libcamera: '%s' did not stop", id_.data());
  return ok_status();
}

void LibcameraCapture::close() {
  if (!impl_) return;
  Impl& m = *impl_;
  const Status stopped = stop();
  if (m.abandoned) {
    (void)std::fprintf(stderr, "camera: %s\n", stopped.error().message);
    abandon();
    return;
  }
  if (m.camera) {
    m.camera->requestCompleted.disconnect(&m, &Impl::on_complete);
    m.camera->disconnected.disconnect(&m, &Impl::on_disconnected);
  }
  m.requests.clear();
  for (std::size_t i = 0; i < m.map.size(); ++i)
    if (m.map[i] != nullptr) ::munmap(m.map[i], m.map_length[i]);
  m.allocator.reset();
  m.config.reset();
  if (m.acquired) m.camera->release();
  m.camera.reset();
  if (m.manager) {
    SharedManager& sm = shared_manager();
    std::lock_guard lock(sm.mutex);
    if (--sm.users == 0 && !sm.abandoned) {
      sm.manager->stop();
      sm.manager.reset();
    }
  }
  impl_.reset();
}

// A lost camera's objects (requests, buffers, mappings, the camera itself) stay
// as libcamera holds them until the process ends; so does the camera manager.
void LibcameraCapture::abandon() {
  Impl* m = impl_.release();
  if (m->manager) {
    SharedManager& sm = shared_manager();
    std::lock_guard lock(sm.mutex);
    sm.abandoned = true;
    --sm.users;
  }
}

Result<RawFrame> LibcameraCapture::next(int timeout_ms) {
  if (!is_open() || !impl_->started)
    return Error::make(Errc::not_ready, "camera: next() while not streaming");
  if (timeout_ms < 0)
    return Error::make(Errc::invalid_argument, "camera: timeout_ms %d < 0", timeout_ms);
  Impl& m = *impl_;
  if (m.held != nullptr) {
    lc::Request* r = m.held;
    m.held = nullptr;
    if (m.requeue(r) < 0) {
      ++health_.device_errors;
      health_.last_fault = FrameFault::device_lost;
      return Error::make(Errc::io_error, "libcamera: '%s' refused a request", id_.data());
    }
  }
  lc::Request* r = m.pop(timeout_ms);
  if (r == nullptr) {
    ++health_.timeouts;
    health_.last_fault = FrameFault::timeout;
    return Error::make(Errc::timeout, "libcamera '%s': no frame within %d ms", id_.data(),
                       timeout_ms);
  }
  m.held = r;
  const lc::FrameBuffer* fb = r->findBuffer(m.stream);
  if (r->status() == lc::Request::RequestCancelled || fb == nullptr ||
      fb->metadata().status == lc::FrameMetadata::FrameCancelled) {
    ++health_.device_errors;
    health_.last_fault = FrameFault::device_lost;
    return Error::make(Errc::io_error, "libcamera '%s': request cancelled (camera stopped or gone)",
                       id_.data());
  }
  const lc::FrameMetadata& md = fb->metadata();
  RawFrame frame;
  frame.data = m.data[fb->cookie()];
  frame.bytes_used = md.planes().empty() ? 0 : md.planes()[0].bytesused;
  frame.sequence = md.sequence;
  frame.time_ns = static_cast<std::int64_t>(md.timestamp);
  frame.driver_error = md.status == lc::FrameMetadata::FrameError;
  FrameFault fault = FrameFault::none;
  if (auto s = m.checker.check(frame, fault); !s) {
    ++health_.rejected;
    health_.last_fault = fault;
    health_.frames_lost += m.checker.lost();
    return Error::make(Errc::parse_error, "libcamera '%s': %s", id_.data(), s.error().message);
  }
  ++health_.frames;
  health_.frames_lost += m.checker.lost();
  return frame;
}

Result<int> LibcameraCapture::flush() {
  if (!is_open() || !impl_->started)
    return Error::make(Errc::not_ready, "camera: flush() while not streaming");
  Impl& m = *impl_;
  int dropped = 0;
  if (m.held != nullptr) {
    lc::Request* r = m.held;
    m.held = nullptr;
    if (m.requeue(r) < 0) return Error::make(Errc::io_error, "libcamera: request refused");
  }
  for (lc::Request* r = m.pop(0); r != nullptr; r = m.pop(0)) {
    ++dropped;
    if (m.requeue(r) < 0) return Error::make(Errc::io_error, "libcamera: request refused");
  }
  m.checker.reset(format_, m.gaps_are_faults);
  return dropped;
}

#else  // built without libcamera

struct LibcameraCapture::Impl {
  bool stream = false;
};
bool libcamera_available() {
  return false;
}
LibcameraCapture::LibcameraCapture() = default;
LibcameraCapture::~LibcameraCapture() = default;
bool LibcameraCapture::is_open() const {
  return false;
}
Status LibcameraCapture::open(const LibcameraCaptureConfig&) {
  return Error::make(Errc::not_ready, "camera: built without libcamera (PETRA_WITH_LIBCAMERA)");
}
Status LibcameraCapture::start() {
  return Error::make(Errc::not_ready, "camera: start() before open()");
}
Status LibcameraCapture::stop() {
  return ok_status();
}
void LibcameraCapture::close() {}
Result<RawFrame> LibcameraCapture::next(int) {
  return Error::make(Errc::not_ready, "camera: next() while not streaming");
}
Result<int> LibcameraCapture::flush() {
  return Error::make(Errc::not_ready, "camera: flush() while not streaming");
}

#endif

}  // namespace petra::hal
