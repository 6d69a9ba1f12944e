#include "tests/support/cached_dir.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <system_error>

namespace petra::test {
namespace {

namespace fs = std::filesystem;

// Holds an exclusive flock on a file for its lifetime.
class FileLock {
 public:
  explicit FileLock(const fs::path& path)
      : fd_(::open(path.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644)) {
    if (fd_ >= 0) ::flock(fd_, LOCK_EX);
  }
  ~FileLock() {
    if (fd_ >= 0) ::close(fd_);  // closing releases the lock
  }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  bool held() const { return fd_ >= 0; }

 private:
  int fd_;
};

std::string read_text(const fs::path& p) {
  std::stringstream s;
  s << std::ifstream(p).rdbuf();
  return s.str();
}

// The copy is current when it was made with this key and after made_by.
bool is_current(const fs::path& dir, const std::string& key, const fs::path& made_by) {
  const fs::path key_file = dir / ".cache_key";
  std::error_code ec;
  if (!fs::exists(key_file, ec) || read_text(key_file) != key) return false;
  const auto made = fs::last_write_time(key_file, ec);
  if (ec) return false;
  const auto program = fs::last_write_time(made_by, ec);
  return !ec && program <= made;
}

}  // namespace

fs::path cached_dir(const std::string& name, const std::string& key, const fs::path& made_by,
                    const std::function<bool(const fs::path&)>& make) {
  const fs::path root = PETRA_TEST_CACHE_DIR;
  std::error_code ec;
  fs::create_directories(root, ec);
  FileLock lock(root / (name + ".lock"));
  if (!lock.held()) return {};
  const fs::path dir = root / name;
  if (is_current(dir, key, made_by)) return dir;

  const fs::path tmp = root / (name + ".tmp");
  fs::remove_all(tmp, ec);
  fs::create_directories(tmp, ec);
  if (ec || !make(tmp)) {
    fs::remove_all(tmp, ec);
    return {};
  }
  std::ofstream(tmp / ".cache_key") << key;
  fs::remove_all(dir, ec);
  fs::rename(tmp, dir, ec);
  return ec ? fs::path{} : dir;
}

fs::path cached_petra_output(const std::string& name, const std::string& petra_bin,
                             const std::string& petra_args) {
  return cached_dir(name, petra_args, petra_bin, [&](const fs::path& out) {
    const std::string cmd =
        petra_bin + " " + petra_args + " --out " + out.string() + " >/dev/null 2>&1";
    return std::system(cmd.c_str()) == 0;
  });
}

fs::path this_executable() {
  std::error_code ec;
  return fs::read_symlink("/proc/self/exe", ec);
}

}  // namespace petra::test
