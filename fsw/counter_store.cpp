#include "fsw/counter_store.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>

namespace petra::fsw {

CounterStore::~CounterStore() {
  if (fd_ >= 0) ::close(fd_);
}

Result<std::uint32_t> CounterStore::open(const char* path) {
  fd_ = ::open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  if (fd_ < 0) return Error::make(Errc::io_error, "counter file %s: cannot open", path);
  char text[16] = {};
  const ssize_t n = ::pread(fd_, text, sizeof(text) - 1, 0);
  if (n <= 0) return std::uint32_t{0};  // new file
  std::uint64_t v = 0;
  ssize_t i = 0;
  while (i < n && text[i] == ' ') ++i;
  const ssize_t digits_from = i;
  for (; i < n && text[i] >= '0' && text[i] <= '9'; ++i)
    v = v * 10 + static_cast<unsigned>(text[i] - '0');
  if (i == digits_from || v > 0xFFFFFFFFull || (i < n && text[i] != '\n'))
    return Error::make(Errc::parse_error, "counter file %s: not a counter", path);
  return static_cast<std::uint32_t>(v);
}

Status CounterStore::store(std::uint32_t counter) {
  if (fd_ < 0) return Error::make(Errc::not_ready, "counter file not open");
  char text[16];
  (void)std::snprintf(text, sizeof(text), "%010u\n", counter);
  if (::pwrite(fd_, text, 11, 0) != 11)
    return Error::make(Errc::io_error, "counter file: write failed");
  return {};
}

}  // namespace petra::fsw
