// The command counter with the shipped programs: `petra keygen` (no overwrite
// without --force, mode 0600, the flight counter beside the key), petra-fsw
// with a configuration that names no counter file refusing after a restart a
// command it accepted before, refusing to start without its counter file
// until --counter-floor, and a new key (keygen --force) opening a new window.
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "hal/udp_link.hpp"

namespace petra {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

int exit_code(int status) {
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

unsigned mode_of(const fs::path& p) {
  struct stat st {};
  return ::stat(p.c_str(), &st) == 0 ? (st.st_mode & 0777) : 0;
}

class Fsw {
 public:
  Fsw(const fs::path& dir, const std::string& extra) {
    pid_ = fork();
    if (pid_ == 0) {
      const std::string cmd = std::string("exec ") + PETRA_FSW_BIN + " --config " +
                              (dir / "fsw.json").string() + " " + extra + " 2>" +
                              (dir / "fsw.err").string();
      execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
  }
  // Waits until it runs (true) or has exited (false, its exit code kept).
  bool running(int wait_ms = 800) {
    std::this_thread::sleep_for(std::chrono::milliseconds(wait_ms));
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == 0) return true;
    code_ = exit_code(status);
    pid_ = -1;
    return false;
  }
  int code() const { return code_; }
  ~Fsw() {
    if (pid_ <= 0) return;
    kill(pid_, SIGTERM);
    waitpid(pid_, nullptr, 0);
  }

 private:
  pid_t pid_ = -1;
  int code_ = -1;
};

TEST(FswCounter, KeygenRestartFloorAndRekeyWithTheShippedPrograms) {
  const fs::path dir =
      fs::temp_directory_path() / ("petra_e2e_counter_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "camera");
  {
    std::ofstream l(dir / "camera/left.pgm", std::ios::binary),
        r(dir / "camera/right.pgm", std::ios::binary);
    l << "P5\n64 48\n255\n" << std::string(64 * 48, '\x40');
    r << "P5\n64 48\n255\n" << std::string(64 * 48, '\x41');
  }
  const std::string cli = PETRA_CLI_BIN;
  const fs::path key = dir / "uplink.key";
  ASSERT_EQ(exit_code(std::system((cli + " keygen --out " + key.string() + " >/dev/null").c_str())),
            0);
  const std::string first_key = slurp(key);
  EXPECT_NE(
      exit_code(std::system((cli + " keygen --out " + key.string() + " 2>/dev/null").c_str())), 0)
      << "an existing key must not be overwritten without --force";
  EXPECT_EQ(slurp(key), first_key);
  EXPECT_EQ(mode_of(key), 0600u);
  EXPECT_EQ(mode_of(dir / "uplink.key.fsw-counter"), 0600u);

  hal::UdpLink a, b;
  ASSERT_TRUE(a.open("127.0.0.1", 0).ok() && b.open("127.0.0.1", 0).ok());
  const std::uint16_t cmd_port = a.local_port(), tlm_port = b.local_port();
  a.close();
  b.close();
  std::ofstream(dir / "fsw.json")
      << R"({"uplink":{"host":"127.0.0.1","port":)" << cmd_port
      << R"(,"key_file":"uplink.key"},"downlink":{"host":"127.0.0.1","port":)" << tlm_port
      << R"(},"budget":{"image_width":64,"image_height":48,"arena_mb":8},
    "camera":{"kind":"file","dir":"camera"}})";
  // petra cmd NOOP with this counter, waiting for the final ack: 0 COMPLETED, 3 REJECTED.
  auto noop = [&](int counter) {
    const std::string c =
        cli + " cmd NOOP --key " + key.string() + " --port " + std::to_string(cmd_port) +
        " --wait --tlm-port " + std::to_string(tlm_port) + " --timeout-ms 3000" +
        (counter > 0 ? " --counter " + std::to_string(counter) : "") + " >/dev/null 2>&1";
    return exit_code(std::system(c.c_str()));
  };

  {
    Fsw fsw(dir, "");
    ASSERT_TRUE(fsw.running()) << slurp(dir / "fsw.err");
    EXPECT_EQ(noop(7), 0);
  }
  {
    Fsw fsw(dir, "");  // restarted, the configuration still names no counter file
    ASSERT_TRUE(fsw.running()) << slurp(dir / "fsw.err");
    EXPECT_EQ(noop(7), 3) << "a command accepted before the restart must be a REPLAY after it";
  }
  fs::remove(dir / "uplink.key.fsw-counter");
  {
    Fsw fsw(dir, "");
    ASSERT_FALSE(fsw.running());
    EXPECT_EQ(fsw.code(), 1);
    EXPECT_NE(slurp(dir / "fsw.err").find("--counter-floor"), std::string::npos)
        << slurp(dir / "fsw.err");
  }
  {
    Fsw fsw(dir, "--counter-floor 7");
    ASSERT_TRUE(fsw.running()) << slurp(dir / "fsw.err");
    EXPECT_EQ(noop(7), 3);
    EXPECT_EQ(noop(8), 0);
  }
  ASSERT_EQ(exit_code(std::system(
                (cli + " keygen --force --out " + key.string() + " >/dev/null").c_str())),
            0);
  EXPECT_NE(slurp(key), first_key);
  {
    Fsw fsw(dir, "");  // a new key: a new counter window, the ground's counter starts again at 1
    ASSERT_TRUE(fsw.running()) << slurp(dir / "fsw.err");
    EXPECT_EQ(noop(0), 0);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace petra
