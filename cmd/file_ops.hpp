// FileOps: the few POSIX file calls the counter store makes, behind an
// interface so a test can cut the power between any two of them (and model
// what a power cut keeps). posix_file_ops() is the real one.
#pragma once

#include <sys/types.h>

#include <cstddef>

namespace petra::cmd {

class FileOps {
 public:
  virtual ~FileOps() = default;
  // Each returns what the POSIX call returns (-1 on error).
  virtual int open(const char* path, int flags, int mode) = 0;
  virtual ssize_t pread(int fd, void* buf, std::size_t n, off_t at) = 0;
  virtual ssize_t write(int fd, const void* buf, std::size_t n) = 0;
  virtual int fsync(int fd) = 0;
  virtual int close(int fd) = 0;
  virtual int rename(const char* from, const char* to) = 0;
};

FileOps& posix_file_ops();

}  // namespace petra::cmd
