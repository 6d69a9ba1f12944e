#include "sim/ground/key_file.hpp"

#include <fcntl.h>
#include <sodium.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "cmd/counter_store.hpp"

namespace petra::ground {

Status write_new_key(const std::string& path, const cmd::AuthKey& key, bool overwrite) {
  // O_EXCL: an existing key is never replaced by accident (the uplink would be lost).
  const int flags = O_WRONLY | O_CREAT | O_CLOEXEC | (overwrite ? O_TRUNC : O_EXCL);
  const int fd = ::open(path.c_str(), flags, 0600);
  if (fd < 0) {
    if (errno == EEXIST)
      return Error::make(Errc::invalid_argument, "%s exists: keep it, or replace it with --force",
                         path.c_str());
    return Error::make(Errc::io_error, "cannot create %s: %s", path.c_str(), std::strerror(errno));
  }
  char hex[2 * cmd::kKeyBytes + 2];
  sodium_bin2hex(hex, sizeof(hex) - 1, key.bytes.data(), key.bytes.size());
  hex[2 * cmd::kKeyBytes] = '\n';
  const bool ok = ::fchmod(fd, 0600) == 0 &&  // an overwritten file keeps its old mode otherwise
                  ::write(fd, hex, sizeof(hex) - 1) == static_cast<ssize_t>(sizeof(hex) - 1) &&
                  ::fsync(fd) == 0;
  sodium_memzero(hex, sizeof(hex));
  if (::close(fd) != 0 || !ok) return Error::make(Errc::io_error, "cannot write %s", path.c_str());
  if (std::remove((path + ".counter").c_str()) != 0 && errno != ENOENT)
    return Error::make(Errc::io_error, "cannot remove the ground counter %s.counter", path.c_str());
  cmd::CounterStore flight;
  PETRA_TRY(flight.bind((path + ".fsw-counter").c_str(), cmd::key_id(key)));
  return flight.store(0);
}

}  // namespace petra::ground
