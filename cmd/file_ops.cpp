#include "cmd/file_ops.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>

namespace petra::cmd {

namespace {

class PosixFileOps final : public FileOps {
 public:
  int open(const char* path, int flags, int mode) override {
    return ::open(path, flags | O_CLOEXEC, mode);
  }
  ssize_t pread(int fd, void* buf, std::size_t n, off_t at) override {
    return ::pread(fd, buf, n, at);
  }
  ssize_t write(int fd, const void* buf, std::size_t n) override { return ::write(fd, buf, n); }
  int fsync(int fd) override { return ::fsync(fd); }
  int close(int fd) override { return ::close(fd); }
  int rename(const char* from, const char* to) override { return std::rename(from, to); }
};

}  // namespace

FileOps& posix_file_ops() {
  static PosixFileOps ops;
  return ops;
}

}  // namespace petra::cmd
