#include "hal/v4l2_capture.hpp"

#include <fcntl.h>
#include <linux/videodev2.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>

#include "hal/errno_text.hpp"

namespace petra::hal {

namespace {

int xioctl(int fd, unsigned long request, void* arg) {
  int r;
  do {
    r = ::ioctl(fd, request, arg);
  } while (r < 0 && errno == EINTR);
  return r;
}

std::int64_t monotonic_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

// Reads a small sysfs text file into buf without its trailing newline.
bool read_sysfs_line(const char* path, char* buf, std::size_t size) {
  const int fd = ::open(path, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const ssize_t n = ::read(fd, buf, size - 1);
  ::close(fd);
  if (n <= 0) return false;
  std::size_t len = static_cast<std::size_t>(n);
  while (len > 0 && (buf[len - 1] == '\n' || buf[len - 1] == ' ')) --len;
  buf[len] = '\0';
  return true;
}

bool device_lost_errno(int err) {
  return err == ENODEV || err == ENXIO || err == EIO || err == EPIPE;
}

}  // namespace

Status find_video_node(const char* name, std::array<char, V4l2CaptureConfig::kMaxName>& path) {
  // Node numbers depend on probe order; names do not. 64 nodes is plenty for a rover.
  for (int n = 0; n < 64; ++n) {
    char sys[80];
    char got[64];
    (void)std::snprintf(sys, sizeof sys, "/sys/class/video4linux/video%d/name", n);
    if (!read_sysfs_line(sys, got, sizeof got)) continue;
    if (std::strcmp(got, name) == 0) {
      (void)std::snprintf(path.data(), path.size(), "/dev/video%d", n);
      return ok_status();
    }
  }
  return Error::make(Errc::io_error, "camera '%s': no /sys/class/video4linux/video*/name matches",
                     name);
}

V4l2Capture::~V4l2Capture() {
  close();
}

Error V4l2Capture::fail_device(const char* what, int err) {
  ++health_.device_errors;
  if (device_lost_errno(err)) health_.last_fault = FrameFault::device_lost;
  return Error::make(Errc::io_error, "%s: %s: %s", path_.data(), what, errno_text(err));
}

Status V4l2Capture::open(const V4l2CaptureConfig& config) {
  close();
  PETRA_TRY(check_config(config));
  gaps_are_faults_ = config.gaps_are_faults;
  if (config.device[0] == '/') {
    (void)std::snprintf(path_.data(), path_.size(), "%s", config.device.data());
  } else {
    PETRA_TRY(find_video_node(config.device.data(), path_));
  }
  PETRA_TRY(open_capture_node());
  auto chosen = choose_format(config);
  if (!chosen) return chosen.error();
  PETRA_TRY(set_format(config, *chosen));
  PETRA_TRY(set_frame_rate(config));
  PETRA_TRY(map_buffers(config));
  checker_.reset(format_, gaps_are_faults_);
  return ok_status();
}

// The configuration's own ranges, before any device is touched.
Status V4l2Capture::check_config(const V4l2CaptureConfig& config) {
  if (config.device[0] == '\0') return Error::make(Errc::missing_field, "camera.device: empty");
  if (config.width <= 0 || config.height <= 0 || config.width > 8192 || config.height > 8192)
    return Error::make(Errc::invalid_argument, "camera: size %dx%d outside 1..8192", config.width,
                       config.height);
  if (config.formats.empty())
    return Error::make(Errc::missing_field, "camera.formats: none configured");
  if (config.buffers < 2 || config.buffers > kMaxBuffers)
    return Error::make(Errc::invalid_argument, "camera.buffers: %d outside 2..%d", config.buffers,
                       kMaxBuffers);
  return ok_status();
}

// Opens path_ and checks it is a streaming video capture node.
Status V4l2Capture::open_capture_node() {
  fd_ = ::open(path_.data(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) return fail_device("open", errno);

  v4l2_capability cap{};
  if (xioctl(fd_, VIDIOC_QUERYCAP, &cap) < 0) {
    const int err = errno;
    close();
    return fail_device("VIDIOC_QUERYCAP (not a V4L2 device?)", err);
  }
  (void)std::snprintf(card_.data(), card_.size(), "%s", reinterpret_cast<const char*>(cap.card));
  const std::uint32_t caps =
      (cap.capabilities & V4L2_CAP_DEVICE_CAPS) != 0 ? cap.device_caps : cap.capabilities;
  if ((caps & V4L2_CAP_VIDEO_CAPTURE) == 0 || (caps & V4L2_CAP_STREAMING) == 0) {
    close();
    return Error::make(Errc::wrong_type, "%s (%s): not a streaming video capture node",
                       path_.data(), card_.data());
  }
  return ok_status();
}

// The first configured format the device lists.
Result<PixelFormat> V4l2Capture::choose_format(const V4l2CaptureConfig& config) {
  bool found = false;
  PixelFormat chosen = config.formats[0];
  for (PixelFormat want : config.formats) {
    for (std::uint32_t i = 0; i < 64 && !found; ++i) {
      v4l2_fmtdesc d{};
      d.index = i;
      d.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
      if (xioctl(fd_, VIDIOC_ENUM_FMT, &d) < 0) break;
      if (d.pixelformat == pixel_format_fourcc(want)) {
        chosen = want;
        found = true;
      }
    }
    if (found) break;
  }
  if (!found) {
    close();
    return Error::make(Errc::wrong_type, "%s (%s): offers none of the configured formats",
                       path_.data(), card_.data());
  }
  return chosen;
}

// Sets the size and format; format_ is what the driver gave.
Status V4l2Capture::set_format(const V4l2CaptureConfig& config, PixelFormat chosen) {
  v4l2_format f{};
  f.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  f.fmt.pix.width = static_cast<std::uint32_t>(config.width);
  f.fmt.pix.height = static_cast<std::uint32_t>(config.height);
  f.fmt.pix.pixelformat = pixel_format_fourcc(chosen);
  f.fmt.pix.field = V4L2_FIELD_NONE;
  if (xioctl(fd_, VIDIOC_S_FMT, &f) < 0) {
    const int err = errno;
    close();
    return fail_device("VIDIOC_S_FMT", err);
  }
  auto pixel = pixel_format_from_fourcc(f.fmt.pix.pixelformat);
  if (!pixel) {
    close();
    return pixel.error();
  }
  format_.pixel = *pixel;
  format_.width = static_cast<int>(f.fmt.pix.width);
  format_.height = static_cast<int>(f.fmt.pix.height);
  format_.bytes_per_line = f.fmt.pix.bytesperline;
  format_.image_bytes = f.fmt.pix.sizeimage;
  if (auto s = check_negotiated(format_, chosen, config.width, config.height); !s) {
    close();
    return Error::make(s.error().code, "%s: %s", path_.data(), s.error().message);
  }
  // Y'CbCr is video range unless the driver says full range; gray is full range
  // unless the driver says otherwise (what V4L2's defaults mean for each).
  if (format_.pixel == PixelFormat::yuyv)
    format_.limited_range = f.fmt.pix.quantization != V4L2_QUANTIZATION_FULL_RANGE &&
                            f.fmt.pix.colorspace != V4L2_COLORSPACE_JPEG;
  else
    format_.limited_range = f.fmt.pix.quantization == V4L2_QUANTIZATION_LIM_RANGE;
  if (f.fmt.pix.field != V4L2_FIELD_NONE) {
    close();
    return Error::make(Errc::wrong_type, "%s: interlaced field order %u, need progressive",
                       path_.data(), f.fmt.pix.field);
  }
  return ok_status();
}

// The configured frame rate, if any, exactly as the driver runs it.
Status V4l2Capture::set_frame_rate(const V4l2CaptureConfig& config) {
  if (config.fps < 0 || config.fps > 1000) {
    close();
    return Error::make(Errc::invalid_argument, "camera.fps: %d outside 0..1000", config.fps);
  }
  if (config.fps == 0) return ok_status();
  v4l2_streamparm parm{};
  parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  parm.parm.capture.timeperframe.numerator = 1;
  parm.parm.capture.timeperframe.denominator = static_cast<std::uint32_t>(config.fps);
  if (xioctl(fd_, VIDIOC_S_PARM, &parm) < 0) {
    const int err = errno;
    close();
    return fail_device("VIDIOC_S_PARM (frame rate)", err);
  }
  const auto& tpf = parm.parm.capture.timeperframe;
  // The driver picks the nearest rate it has: anything else than asked is refused.
  if ((parm.parm.capture.capability & V4L2_CAP_TIMEPERFRAME) == 0 || tpf.numerator == 0 ||
      static_cast<std::uint64_t>(tpf.denominator) * 100 <
          static_cast<std::uint64_t>(tpf.numerator) * static_cast<std::uint64_t>(config.fps) * 99 ||
      static_cast<std::uint64_t>(tpf.denominator) * 100 >
          static_cast<std::uint64_t>(tpf.numerator) * static_cast<std::uint64_t>(config.fps) *
              101) {
    close();
    return Error::make(Errc::invalid_argument, "%s: device runs at %u/%u fps, configured %d",
                       path_.data(), tpf.denominator, tpf.numerator, config.fps);
  }
  return ok_status();
}

// Requests the driver's buffers and maps each one.
Status V4l2Capture::map_buffers(const V4l2CaptureConfig& config) {
  v4l2_requestbuffers req{};
  req.count = static_cast<std::uint32_t>(config.buffers);
  req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  req.memory = V4L2_MEMORY_MMAP;
  if (xioctl(fd_, VIDIOC_REQBUFS, &req) < 0) {
    const int err = errno;
    close();
    return fail_device("VIDIOC_REQBUFS", err);
  }
  if (req.count < 2 || req.count > static_cast<std::uint32_t>(kMaxBuffers)) {
    close();
    return Error::make(Errc::capacity_exceeded, "%s: driver gave %u buffers, need 2..%d",
                       path_.data(), req.count, kMaxBuffers);
  }
  buffer_count_ = static_cast<int>(req.count);
  for (int i = 0; i < buffer_count_; ++i) {
    v4l2_buffer b{};
    b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    b.memory = V4L2_MEMORY_MMAP;
    b.index = static_cast<std::uint32_t>(i);
    if (xioctl(fd_, VIDIOC_QUERYBUF, &b) < 0) {
      const int err = errno;
      close();
      return fail_device("VIDIOC_QUERYBUF", err);
    }
    void* p = ::mmap(nullptr, b.length, PROT_READ | PROT_WRITE, MAP_SHARED, fd_, b.m.offset);
    if (p == MAP_FAILED) {
      const int err = errno;
      close();
      return fail_device("mmap", err);
    }
    memory_[static_cast<std::size_t>(i)] = static_cast<std::uint8_t*>(p);
    length_[static_cast<std::size_t>(i)] = b.length;
  }
  return ok_status();
}

Status V4l2Capture::start() {
  if (fd_ < 0) return Error::make(Errc::not_ready, "camera: start() before open()");
  if (streaming_) return ok_status();
  for (int i = 0; i < buffer_count_; ++i) {
    v4l2_buffer b{};
    b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    b.memory = V4L2_MEMORY_MMAP;
    b.index = static_cast<std::uint32_t>(i);
    if (xioctl(fd_, VIDIOC_QBUF, &b) < 0) return fail_device("VIDIOC_QBUF", errno);
  }
  int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  if (xioctl(fd_, VIDIOC_STREAMON, &type) < 0) return fail_device("VIDIOC_STREAMON", errno);
  streaming_ = true;
  held_ = -1;
  checker_.reset(format_, gaps_are_faults_);
  return ok_status();
}

Status V4l2Capture::stop() {
  if (fd_ < 0 || !streaming_) return ok_status();
  streaming_ = false;
  held_ = -1;  // STREAMOFF takes every buffer back
  int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  if (xioctl(fd_, VIDIOC_STREAMOFF, &type) < 0) return fail_device("VIDIOC_STREAMOFF", errno);
  return ok_status();
}

void V4l2Capture::close() {
  if (fd_ >= 0) {
    (void)stop();
    for (int i = 0; i < buffer_count_; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (memory_[k] != nullptr) ::munmap(memory_[k], length_[k]);
      memory_[k] = nullptr;
      length_[k] = 0;
    }
    ::close(fd_);
  }
  fd_ = -1;
  streaming_ = false;
  held_ = -1;
  buffer_count_ = 0;
}

Status V4l2Capture::requeue_held() {
  if (held_ < 0) return ok_status();
  v4l2_buffer b{};
  b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  b.memory = V4L2_MEMORY_MMAP;
  b.index = static_cast<std::uint32_t>(held_);
  held_ = -1;
  if (xioctl(fd_, VIDIOC_QBUF, &b) < 0) return fail_device("VIDIOC_QBUF", errno);
  return ok_status();
}

// Dequeues one ready buffer (got=false when none is ready) and marks it held.
Status V4l2Capture::dequeue(RawFrame& out, bool& got) {
  got = false;
  v4l2_buffer b{};
  b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  b.memory = V4L2_MEMORY_MMAP;
  if (xioctl(fd_, VIDIOC_DQBUF, &b) < 0) {
    if (errno == EAGAIN) return ok_status();
    return fail_device("VIDIOC_DQBUF", errno);
  }
  if (b.index >= static_cast<std::uint32_t>(buffer_count_)) {
    ++health_.device_errors;
    return Error::make(Errc::io_error, "%s: driver returned buffer %u of %d", path_.data(), b.index,
                       buffer_count_);
  }
  held_ = static_cast<int>(b.index);
  got = true;
  out.data = memory_[b.index];
  out.bytes_used = b.bytesused;
  out.sequence = b.sequence;
  out.time_ns = static_cast<std::int64_t>(b.timestamp.tv_sec) * 1'000'000'000 +
                static_cast<std::int64_t>(b.timestamp.tv_usec) * 1000;
  out.driver_error = (b.flags & V4L2_BUF_FLAG_ERROR) != 0;
  // A driver that does not stamp buffers (or copies a stamp from elsewhere)
  // gets the dequeue time, so the skew and ordering checks still mean something.
  if ((b.flags & V4L2_BUF_FLAG_TIMESTAMP_MASK) != V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC)
    out.time_ns = monotonic_ns();
  if (out.bytes_used > length_[b.index])
    out.bytes_used = static_cast<std::uint32_t>(length_[b.index]);
  return ok_status();
}

Result<RawFrame> V4l2Capture::next(int timeout_ms) {
  if (fd_ < 0 || !streaming_)
    return Error::make(Errc::not_ready, "camera: next() while not streaming");
  if (timeout_ms < 0)
    return Error::make(Errc::invalid_argument, "camera: timeout_ms %d < 0", timeout_ms);
  PETRA_TRY(requeue_held());
  const std::int64_t deadline = monotonic_ns() + static_cast<std::int64_t>(timeout_ms) * 1'000'000;
  bool poll_error = false;
  for (;;) {
    RawFrame frame;
    bool got = false;
    PETRA_TRY(dequeue(frame, got));
    if (got) {
      FrameFault fault = FrameFault::none;
      if (auto s = checker_.check(frame, fault); !s) {
        ++health_.rejected;
        health_.last_fault = fault;
        health_.frames_lost += checker_.lost();
        PETRA_TRY(requeue_held());
        return Error::make(Errc::parse_error, "%s: %s", path_.data(), s.error().message);
      }
      ++health_.frames;
      health_.frames_lost += checker_.lost();
      return frame;
    }
    // poll() said error and no frame is waiting: the stream stopped or the device went away.
    if (poll_error) {
      ++health_.device_errors;
      health_.last_fault = FrameFault::device_lost;
      return Error::make(Errc::io_error, "%s (%s): stream stopped or device lost", path_.data(),
                         card_.data());
    }
    const std::int64_t left_ns = deadline - monotonic_ns();
    if (left_ns <= 0) {
      ++health_.timeouts;
      health_.last_fault = FrameFault::timeout;
      return Error::make(Errc::timeout, "%s (%s): no frame within %d ms", path_.data(),
                         card_.data(), timeout_ms);
    }
    pollfd p{fd_, POLLIN, 0};
    const int wait_ms = static_cast<int>((left_ns + 999'999) / 1'000'000);
    const int r = ::poll(&p, 1, wait_ms);
    if (r < 0 && errno != EINTR) return fail_device("poll", errno);
    poll_error =
        r > 0 && (p.revents & (POLLERR | POLLHUP | POLLNVAL)) != 0 && (p.revents & POLLIN) == 0;
  }
}

Result<int> V4l2Capture::flush() {
  if (fd_ < 0 || !streaming_)
    return Error::make(Errc::not_ready, "camera: flush() while not streaming");
  PETRA_TRY(requeue_held());
  int dropped = 0;
  for (int i = 0; i < kMaxBuffers * 2; ++i) {
    RawFrame frame;
    bool got = false;
    PETRA_TRY(dequeue(frame, got));
    if (!got) break;
    ++dropped;
    PETRA_TRY(requeue_held());
  }
  checker_.reset(format_, gaps_are_faults_);
  return dropped;
}

}  // namespace petra::hal
