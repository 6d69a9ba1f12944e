#include "hal/file_stereo_camera.hpp"

#include <dirent.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <ctime>

namespace petra::hal {

namespace {

std::int64_t realtime_ns() {
  timespec ts{};
  ::clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

bool is_left_pgm(const char* name) {
  const std::size_t n = std::strlen(name);
  return n >= 8 && std::strncmp(name, "left", 4) == 0 && std::strcmp(name + n - 4, ".pgm") == 0;
}

}  // namespace

Status FileStereoCamera::open(const char* dir) {
  pairs_.clear();
  DIR* d = ::opendir(dir);  // init only: opendir allocates
  if (d == nullptr) return Error::make(Errc::io_error, "camera folder %s: cannot open", dir);
  bool overflow = false;
  for (dirent* e = ::readdir(d); e != nullptr; e = ::readdir(d)) {
    if (!is_left_pgm(e->d_name)) continue;
    Pair p;
    const int nl = std::snprintf(p.left.data(), kMaxPath, "%s/%s", dir, e->d_name);
    const int nr = std::snprintf(p.right.data(), kMaxPath, "%s/right%s", dir, e->d_name + 4);
    if (nl < 0 || nr < 0 || nl >= static_cast<int>(kMaxPath) || nr >= static_cast<int>(kMaxPath))
      continue;
    if (::access(p.right.data(), R_OK) != 0) continue;
    if (!pairs_.push_back(p)) overflow = true;
  }
  ::closedir(d);
  if (overflow)
    return Error::make(Errc::capacity_exceeded, "camera folder %s: more than %zu pairs", dir,
                       kMaxPairs);
  if (pairs_.empty())
    return Error::make(Errc::invalid_argument,
                       "camera folder %s: no left*.pgm with a matching right*.pgm", dir);
  // Name order, so a folder plays back the same sequence every time (insertion sort: n <= 64).
  for (std::size_t i = 1; i < pairs_.size(); ++i)
    for (std::size_t j = i;
         j > 0 && std::strcmp(pairs_[j - 1].left.data(), pairs_[j].left.data()) > 0; --j) {
      const Pair t = pairs_[j];
      pairs_[j] = pairs_[j - 1];
      pairs_[j - 1] = t;
    }
  auto first = reader_.read_size(pairs_[0].left.data());
  if (!first) return first.error();
  size_ = *first;
  for (const Pair& p : pairs_) {
    for (const char* path : {p.left.data(), p.right.data()}) {
      auto s = reader_.read_size(path);
      if (!s) return s.error();
      if (s->width != size_.width || s->height != size_.height)
        return Error::make(Errc::invalid_argument, "%s: %dx%d px, first pair is %dx%d", path,
                           s->width, s->height, size_.width, size_.height);
    }
  }
  next_ = 0;
  sequence_ = 0;
  skipped_ = 0;
  return {};
}

Result<FrameMeta> FileStereoCamera::acquire(Gray8View left, Gray8View right) {
  if (pairs_.empty()) return Error::make(Errc::not_ready, "file camera: not open");
  // The next call takes the next pair whatever this one gives: a corrupt pair
  // fails once per cycle through the folder, never every call.
  const std::size_t index = next_;
  const Pair& p = pairs_[index];
  next_ = (next_ + 1) % pairs_.size();
  FrameMeta meta;
  meta.source_index = static_cast<std::uint32_t>(index);
  Status s = reader_.read(p.left.data(), left);
  meta.left_time_ns = realtime_ns();
  if (s) s = reader_.read(p.right.data(), right);
  if (!s) {
    ++skipped_;
    return Error::make(s.code(), "pair %zu of %zu skipped: %s", index + 1, pairs_.size(),
                       s.error().message);
  }
  meta.right_time_ns = meta.left_time_ns;  // one instant: files carry no capture time
  meta.sequence = ++sequence_;
  return meta;
}

}  // namespace petra::hal
