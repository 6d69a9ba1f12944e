// CounterStore: the last accepted command counter, kept in a small file so a
// reboot or a power cut never reopens the door to replays (the anti-replay
// sequence number of CCSDS SDLS). The file is one line, the counter and the
// key it belongs to (cmd::key_id): "0000000042 0123456789abcdef\n"; a file
// without the key id ("0000000042\n", older releases) counts as the current
// key's. Each update is written to PATH.tmp, fsync'd, renamed over PATH and
// the folder fsync'd, all before the command it admits runs: a power cut at
// any step leaves the old or the new counter, and the new one once store()
// returned. No heap: paths live in fixed arrays.
#pragma once

#include <array>
#include <cstdint>

#include "algo/core/result.hpp"
#include "cmd/auth.hpp"
#include "cmd/file_ops.hpp"

namespace petra::cmd {

struct StoredCounter {
  bool exists = false;   // false: no counter file
  bool same_key = true;  // false: the file belongs to another key (re-keyed)
  std::uint32_t counter = 0;
};

class CounterStore {
 public:
  static constexpr std::size_t kPathBytes = 272;

  // Where (PATH, PATH.tmp, PATH's folder) and for which key; touches nothing.
  Status bind(const char* path, const KeyId& key, FileOps* ops = &posix_file_ops());
  // The file as it is; an error names the file when it is unreadable or not a counter file.
  Result<StoredCounter> load();
  // Durably records `counter` for the bound key (the steps above).
  Status store(std::uint32_t counter);

  bool is_bound() const { return ops_ != nullptr; }
  const char* path() const { return path_.data(); }

 private:
  Status write_tmp(const char* text, std::size_t size);
  Status sync_folder();

  FileOps* ops_ = nullptr;
  KeyId key_{};
  std::array<char, kPathBytes> path_{};
  std::array<char, kPathBytes + 4> tmp_{};
  std::array<char, kPathBytes> dir_{};
};

}  // namespace petra::cmd
