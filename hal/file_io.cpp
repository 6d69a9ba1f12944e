#include "hal/file_io.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "hal/errno_text.hpp"

namespace petra::hal {

Result<std::size_t> read_small_file(const char* path, std::span<char> buf) {
  const int fd = ::open(path, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return Error::make(Errc::io_error, "%s: cannot open (%s)", path, errno_text(errno));
  std::size_t used = 0;
  for (;;) {  // bounded by the buffer size
    const ssize_t n = ::read(fd, buf.data() + used, buf.size() - used);
    if (n < 0) {
      const int why = errno;
      ::close(fd);
      return Error::make(Errc::io_error, "%s: cannot read (%s)", path, errno_text(why));
    }
    if (n == 0) break;
    used += static_cast<std::size_t>(n);
    if (used == buf.size()) {
      char extra = 0;
      const ssize_t more = ::read(fd, &extra, 1);
      ::close(fd);
      if (more > 0)
        return Error::make(Errc::capacity_exceeded, "%s: larger than %zu bytes", path, buf.size());
      return used;
    }
  }
  ::close(fd);
  return used;
}

Status write_small_file(const char* path, std::span<const char> data) {
  char tmp[512];
  if (std::snprintf(tmp, sizeof(tmp), "%s.tmp", path) >= static_cast<int>(sizeof(tmp)))
    return Error::make(Errc::invalid_argument, "path too long: %s", path);
  const int fd = ::open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) return Error::make(Errc::io_error, "%s: cannot create (%s)", tmp, errno_text(errno));
  const ssize_t n = ::write(fd, data.data(), data.size());
  const int write_errno = errno;
  const bool ok = n == static_cast<ssize_t>(data.size());
  ::close(fd);
  if (!ok)
    return Error::make(Errc::io_error, "%s: cannot write (%s)", tmp,
                       n < 0 ? errno_text(write_errno) : "short write");
  if (::rename(tmp, path) != 0)
    return Error::make(Errc::io_error, "%s: cannot rename to %s (%s)", tmp, path,
                       errno_text(errno));
  return {};
}

Status join_path(const char* dir, const char* name, std::span<char> out) {
  int n = 0;
  if (name[0] == '/' || dir == nullptr || dir[0] == '\0')
    n = std::snprintf(out.data(), out.size(), "%s", name);
  else
    n = std::snprintf(out.data(), out.size(), "%s/%s", dir, name);
  if (n < 0 || static_cast<std::size_t>(n) >= out.size())
    return Error::make(Errc::capacity_exceeded, "path too long: %s/%s", dir, name);
  return {};
}

}  // namespace petra::hal
