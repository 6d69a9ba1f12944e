// The shipped programs end to end over loopback UDP: a petra-fsw process with
// a file camera, `petra cmd` signing and sending, `petra tlm --json` receiving.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "cmd/command_packet.hpp"
#include "hal/udp_link.hpp"

namespace petra {
namespace {

namespace fs = std::filesystem;

pid_t spawn_shell(const std::string& command) {
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

int stop(pid_t pid) {
  kill(pid, SIGTERM);
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Two distinct free ports: both sockets are held while the second is chosen.
std::pair<std::uint16_t, std::uint16_t> two_free_udp_ports() {
  hal::UdpLink a, b;
  EXPECT_TRUE(a.open("127.0.0.1", 0).ok());
  EXPECT_TRUE(b.open("127.0.0.1", 0).ok());
  return {a.local_port(), b.local_port()};
}

// True once some socket is bound to this UDP port (IPv4), read from the
// kernel's table: a probe bind would itself take the port for a moment and
// could make the program it waits for fail its own bind.
bool udp_port_bound(std::uint16_t port) {
  std::ifstream f("/proc/net/udp");
  std::string line;
  std::getline(f, line);  // header
  while (std::getline(f, line)) {
    std::istringstream fields(line);
    std::string slot, local;
    fields >> slot >> local;
    const auto colon = local.find(':');
    if (colon != std::string::npos && std::stoul(local.substr(colon + 1), nullptr, 16) == port)
      return true;
  }
  return false;
}

std::string read_text(const fs::path& path) {
  std::ifstream f(path);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

long rss_kb(pid_t pid) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

void write_pgm(const fs::path& path, int w, int h, int seed) {
  std::ofstream f(path, std::ios::binary);
  f << "P5\n" << w << " " << h << "\n255\n";
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) f.put(static_cast<char>((x + 2 * y + seed) & 0xFF));
}

bool contains_line(const std::vector<std::string>& lines,
                   std::initializer_list<const char*> parts) {
  for (const auto& l : lines) {
    bool all = true;
    for (const char* p : parts) all = all && l.find(p) != std::string::npos;
    if (all) return true;
  }
  return false;
}

TEST(FswLoopback, PetraCmdAndPetraTlmTalkToTheFlightProcess) {
  const fs::path dir = fs::temp_directory_path() / ("petra_e2e_" + std::to_string(getpid()));
  fs::create_directories(dir / "camera");
  fs::create_directories(dir / "products");
  write_pgm(dir / "camera/left.pgm", 320, 240, 0);
  write_pgm(dir / "camera/right.pgm", 320, 240, 3);
  const std::string cli = PETRA_CLI_BIN;
  ASSERT_EQ(
      std::system((cli + " keygen --out " + (dir / "uplink.key").string() + " >/dev/null").c_str()),
      0);
  ASSERT_EQ(
      std::system((cli + " keygen --out " + (dir / "forger.key").string() + " >/dev/null").c_str()),
      0);
  const auto [cmd_port, tlm_port] = two_free_udp_ports();
  std::ofstream(dir / "fsw.json") << R"({"uplink":{"host":"127.0.0.1","port":)" << cmd_port
                                  << R"(,"key_file":"uplink.key"},
    "downlink":{"host":"127.0.0.1","port":)"
                                  << tlm_port << R"(},
    "loop":{"cycle_ms":10},"budget":{"image_width":320,"image_height":240,"arena_mb":4,"tlm_queue_packets":256},
    "camera":{"kind":"file","dir":"camera"}})";

  const pid_t tlm = spawn_shell(cli + " tlm --follow --json --port " + std::to_string(tlm_port) +
                                " --save-products " + (dir / "products").string() + " > " +
                                (dir / "tlm.jsonl").string() + " 2>" + (dir / "tlm.err").string());
  // petra tlm must be listening before petra-fsw boots, or the boot event is lost.
  bool listening = false;
  for (int i = 0; i < 1000 && !listening; ++i) {
    listening = udp_port_bound(tlm_port);
    if (!listening) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!listening) stop(tlm);  // leave no receiver behind
  ASSERT_TRUE(listening) << "petra tlm is not listening on " << tlm_port
                         << " after 10 s: " << read_text(dir / "tlm.err");
  const pid_t fsw = spawn_shell(std::string(PETRA_FSW_BIN) + " --config " +
                                (dir / "fsw.json").string() + " 2>" + (dir / "fsw.err").string());
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ASSERT_EQ(waitpid(fsw, nullptr, WNOHANG), 0) << "petra-fsw exited at boot";

  const std::string send = cli + " cmd --key " + (dir / "uplink.key").string() + " --port " +
                           std::to_string(cmd_port) + " ";
  for (const char* c :
       {"NOOP",
        "SELECT_ROI x_px=40 y_px=30 w_px=200 h_px=150 planes=2 click_u_px=100 click_v_px=90",
        "ACQUIRE", "EVALUATE acquire=0", "GET_PARAM param_id=8"}) {
    ASSERT_EQ(std::system((send + c + " >/dev/null").c_str()), 0) << c;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  // A forged command (another key) and a command outside its range: refused by petra cmd itself.
  ASSERT_EQ(std::system((cli + " cmd --key " + (dir / "forger.key").string() + " --port " +
                         std::to_string(cmd_port) + " NOOP >/dev/null")
                            .c_str()),
            0);
  EXPECT_NE(std::system((send + "SELECT_ROI planes=12 2>/dev/null").c_str()), 0);

  // Resident memory stays flat across 1,000 more commands straight from a test sender.
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const long rss_before = rss_kb(fsw);
  {
    ASSERT_TRUE(cmd::auth_init().ok());
    std::ifstream kf(dir / "uplink.key");
    std::string hex;
    kf >> hex;
    const cmd::AuthKey key = *cmd::parse_key_hex(std::span<const char>(hex.data(), hex.size()));
    hal::UdpLink s;
    ASSERT_TRUE(s.open("127.0.0.1", 0).ok());
    ASSERT_TRUE(s.set_peer("127.0.0.1", cmd_port).ok());
    std::vector<std::uint8_t> p(cmd::kMaxCommandBytes);
    for (std::uint32_t i = 0; i < 1000; ++i) {
      const auto n = cmd::encode_command_packet(
          {cmd::FunctionCode::NOOP, 1000 + i, cmd::NoopArgs{}}, 0, key, p);
      s.send(std::span(p).first(*n));
      if (i % 8 == 7) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1200));  // one more housekeeping packet
  const long rss_after = rss_kb(fsw);
  EXPECT_EQ(stop(fsw), 0) << "petra-fsw did not stop cleanly on SIGTERM";
  stop(tlm);

  std::vector<std::string> lines;
  std::ifstream in(dir / "tlm.jsonl");
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  ASSERT_FALSE(lines.empty()) << "petra tlm: " << read_text(dir / "tlm.err")
                              << "petra-fsw: " << read_text(dir / "fsw.err");
  EXPECT_TRUE(contains_line(lines, {"\"packet\":\"EVENT\"", "boot complete"}));
  EXPECT_TRUE(contains_line(lines, {"\"packet\":\"HK\""}));
  EXPECT_TRUE(contains_line(
      lines, {"\"packet\":\"ACK\"", "\"function_code\":1,", "\"counter\":1,", "\"stage\":3"}));
  EXPECT_TRUE(contains_line(lines, {"\"packet\":\"ACK\"", "\"function_code\":16,", "\"stage\":3"}));
  EXPECT_TRUE(contains_line(lines, {"\"packet\":\"ACK\"", "\"function_code\":17,", "\"stage\":3"}));
  EXPECT_TRUE(
      contains_line(lines, {"\"packet\":\"EVENT\"", "ROI x 40, y 30, 200 x 150 px selected"}));
  EXPECT_TRUE(
      contains_line(lines, {"\"packet\":\"PARAM_VALUE\"", "\"param_id\":8,", "\"value\":4"}));
  // No calib.json configured: EVALUATE fails PIPELINE_ERROR and the event names why.
  EXPECT_TRUE(contains_line(
      lines, {"\"packet\":\"ACK\"", "\"function_code\":18,", "\"stage\":4", "\"reason\":36"}));
  EXPECT_TRUE(contains_line(lines, {"\"packet\":\"EVENT\"", "failed: not_ready in step RECTIFY"}));
  // The forged NOOP: rejected for its MAC, with the reason's own event.
  EXPECT_TRUE(contains_line(lines, {"\"packet\":\"ACK\"", "\"stage\":2", "\"reason\":6"}));
  EXPECT_TRUE(contains_line(lines, {"\"packet\":\"EVENT\"", "HMAC-SHA256 does not verify"}));
  // The left image came down in chunks and was reassembled.
  EXPECT_EQ(fs::file_size(dir / "products/left_image_1.pgm"), 320u * 240u + 15u);
  std::size_t completed = 0;
  for (const auto& l : lines)
    if (l.find("\"packet\":\"ACK\"") != std::string::npos &&
        l.find("\"function_code\":1,") != std::string::npos &&
        l.find("\"stage\":3") != std::string::npos)
      ++completed;
  EXPECT_GE(completed, 950u) << "NOOPs completed out of 1001 (UDP on a loaded host may drop a few)";
  EXPECT_LE(rss_after - rss_before, 64) << "RSS " << rss_before << " -> " << rss_after << " kB";
  std::printf(
      "[ figures  ] %zu telemetry lines, %zu NOOPs completed, petra-fsw RSS %ld -> %ld kB\n",
      lines.size(), completed, rss_before, rss_after);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace petra
