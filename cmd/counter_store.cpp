#include "cmd/counter_store.hpp"

#include <fcntl.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace petra::cmd {

namespace {

constexpr std::size_t kLineBytes = 28;  // "%010u %016x\n"

// The file is written with %016x: lower case only.
int lower_hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

// "DDDDDDDDDD\n" (no key id) or "DDDDDDDDDD HHHHHHHHHHHHHHHH\n"; false when neither.
bool parse_line(const char* text, std::size_t n, const KeyId& key, StoredCounter& out) {
  std::size_t i = 0;
  std::uint64_t v = 0;
  for (; i < n && i < 11 && text[i] >= '0' && text[i] <= '9'; ++i)
    v = v * 10 + static_cast<unsigned>(text[i] - '0');
  if (i == 0 || i > 10 || v > 0xFFFFFFFFull) return false;
  out.counter = static_cast<std::uint32_t>(v);
  if (i + 1 == n && text[i] == '\n') return true;  // no key id: the current key's
  if (n != i + 2 + 2 * key.size() || text[i] != ' ' || text[n - 1] != '\n') return false;
  bool same = true;
  for (std::size_t k = 0; k < key.size(); ++k) {
    const int hi = lower_hex_value(text[i + 1 + 2 * k]);
    const int lo = lower_hex_value(text[i + 2 + 2 * k]);
    if (hi < 0 || lo < 0) return false;
    same = same && static_cast<std::uint8_t>(hi * 16 + lo) == key[k];
  }
  out.same_key = same;
  return true;
}

}  // namespace

Status CounterStore::bind(const char* path, const KeyId& key, FileOps* ops) {
  const std::size_t len = std::strlen(path);
  if (len == 0 || len >= path_.size())
    return Error::make(Errc::invalid_argument, "counter file: path empty or too long");
  std::memcpy(path_.data(), path, len + 1);
  (void)std::snprintf(tmp_.data(), tmp_.size(), "%s.tmp", path);
  const char* slash = std::strrchr(path, '/');
  if (slash == nullptr)
    (void)std::snprintf(dir_.data(), dir_.size(), ".");
  else if (slash == path)
    (void)std::snprintf(dir_.data(), dir_.size(), "/");
  else
    (void)std::snprintf(dir_.data(), dir_.size(), "%.*s", static_cast<int>(slash - path), path);
  key_ = key;
  ops_ = ops;
  return {};
}

Result<StoredCounter> CounterStore::load() {
  if (ops_ == nullptr) return Error::make(Errc::not_ready, "counter file: not bound");
  StoredCounter out;
  const int fd = ops_->open(path_.data(), O_RDONLY, 0);
  if (fd < 0) {
    if (errno == ENOENT) return out;
    return Error::make(Errc::io_error, "counter file %s: %s", path_.data(), std::strerror(errno));
  }
  char text[kLineBytes + 2] = {};
  const ssize_t n = ops_->pread(fd, text, sizeof(text), 0);
  (void)ops_->close(fd);
  out.exists = true;
  if (n <= 0 || !parse_line(text, static_cast<std::size_t>(n), key_, out))
    return Error::make(Errc::parse_error, "counter file %s: not a counter file", path_.data());
  return out;
}

Status CounterStore::write_tmp(const char* text, std::size_t size) {
  const int fd = ops_->open(tmp_.data(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  if (fd < 0) return Error::make(Errc::io_error, "counter file %s: cannot create", tmp_.data());
  const bool written = ops_->write(fd, text, size) == static_cast<ssize_t>(size);
  const bool synced = written && ops_->fsync(fd) == 0;  // the data before the name
  const bool closed = ops_->close(fd) == 0;
  if (!written || !synced || !closed)
    return Error::make(Errc::io_error, "counter file %s: write failed", tmp_.data());
  return {};
}

Status CounterStore::sync_folder() {
  const int fd = ops_->open(dir_.data(), O_RDONLY | O_DIRECTORY, 0);
  if (fd < 0)
    return Error::make(Errc::io_error, "counter file folder %s: cannot open", dir_.data());
  const bool synced = ops_->fsync(fd) == 0;  // the rename itself survives a power cut
  (void)ops_->close(fd);
  if (!synced)
    return Error::make(Errc::io_error, "counter file folder %s: fsync failed", dir_.data());
  return {};
}

Status CounterStore::store(std::uint32_t counter) {
  if (ops_ == nullptr) return Error::make(Errc::not_ready, "counter file: not bound");
  char text[kLineBytes + 1];
  const int n =
      std::snprintf(text, sizeof(text), "%010u %02x%02x%02x%02x%02x%02x%02x%02x\n", counter,
                    key_[0], key_[1], key_[2], key_[3], key_[4], key_[5], key_[6], key_[7]);
  PETRA_TRY(write_tmp(text, static_cast<std::size_t>(n)));
  if (ops_->rename(tmp_.data(), path_.data()) != 0)
    return Error::make(Errc::io_error, "counter file %s: rename failed", path_.data());
  return sync_folder();
}

}  // namespace petra::cmd
