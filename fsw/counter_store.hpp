// CounterStore: the last accepted command counter, kept in a small file so a
// reboot does not reopen the door to replays. The file is opened at init and
// each update is one 11-byte pwrite of a fixed-width decimal ("0000000042\n"):
// microseconds in the loop, never a partial number.
#pragma once

#include <cstdint>

#include "algo/core/result.hpp"

namespace petra::fsw {

class CounterStore {
 public:
  CounterStore() = default;
  ~CounterStore();
  CounterStore(const CounterStore&) = delete;
  CounterStore& operator=(const CounterStore&) = delete;

  // Opens (creating) the file; returns the stored counter, 0 for a new file.
  Result<std::uint32_t> open(const char* path);
  Status store(std::uint32_t counter);
  bool is_open() const { return fd_ >= 0; }

 private:
  int fd_ = -1;
};

}  // namespace petra::fsw
