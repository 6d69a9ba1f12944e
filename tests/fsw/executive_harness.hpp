// An executive in-process with its real UDP links on loopback, a file camera
// over a generated PGM pair in a temporary folder, and a ground side that
// signs commands and decodes telemetry like `petra cmd` / `petra tlm`.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cmd/command_packet.hpp"
#include "fsw/executive.hpp"
#include "hal/clock.hpp"
#include "hal/file_stereo_camera.hpp"
#include "tests/fsw/scripted_pipeline_job.hpp"
#include "tlm/telemetry.hpp"

namespace petra::test {

inline void write_pgm(const std::string& path, int w, int h, int seed) {
  std::ofstream f(path, std::ios::binary);
  f << "P5\n" << w << " " << h << "\n255\n";
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) f.put(static_cast<char>((x * 7 + y * 3 + seed) & 0xFF));
}

inline const char* kKeyHex = "000102030405060708090a0b0c0d0e0f101112131415161718191a1b1c1d1e1f";

class ExecutiveHarness {
 public:
  static constexpr int kWidth = 160;
  static constexpr int kHeight = 120;

  explicit ExecutiveHarness(std::string extra_config = "", bool with_job = true,
                            std::string dir_name = "")
      : with_job_(with_job) {
    dir_ = dir_name.empty()
               ? std::filesystem::temp_directory_path() /
                     ("petra_fsw_" + std::to_string(::getpid()) + "_" + std::to_string(next_id()))
               : std::filesystem::path(dir_name);
    std::filesystem::create_directories(dir_ / "camera");
    write_pgm((dir_ / "camera/left_000.pgm").string(), kWidth, kHeight, 0);
    write_pgm((dir_ / "camera/right_000.pgm").string(), kWidth, kHeight, 5);
    std::ofstream(dir_ / "key.hex") << kKeyHex << "\n";
    // A new key's counter file, as `petra keygen` writes it (kept when the folder is reused).
    if (!std::filesystem::exists(dir_ / "counter.txt"))
      std::ofstream(dir_ / "counter.txt") << "0\n";
    EXPECT_TRUE(ground_.open("127.0.0.1", 0).ok());
    extra_ = std::move(extra_config);
  }
  ~ExecutiveHarness() {
    exec_.shutdown();
    if (!keep_dir_) std::filesystem::remove_all(dir_);
  }

  // Writes the configuration and boots the executive.
  Status boot() {
    const std::string cfg =
        R"({"uplink":{"host":"127.0.0.1","port":0,"key_file":"key.hex")" +
        (counter_file.empty() ? std::string() : R"(,"counter_file":")" + counter_file + "\"") +
        uplink_extra + R"(},
      "downlink":{"host":"127.0.0.1","port":)" +
        std::to_string(ground_.local_port()) + R"(},"loop":)" + loop + R"(,
      "budget":)" +
        (budget.empty()
             ? R"({"image_width":320,"image_height":240,"arena_mb":1,"tlm_queue_packets":)" +
                   std::to_string(queue_packets) + R"(,"worker_stack_kb":256,"cloud_points":100})"
             : budget) +
        R"(,
      "camera":{"kind":"file","dir":"camera"})" +
        extra_ + "}";
    std::ofstream(dir_ / "fsw.json") << cfg;
    auto config = fsw::load_config((dir_ / "fsw.json").c_str());
    if (!config) return config.error();
    PETRA_TRY(camera_.open(config->camera_dir.data()));
    fsw::Dependencies deps;
    deps.camera = camera != nullptr ? camera : &camera_;
    deps.clock = &clock_;
    deps.job = pipeline != nullptr ? pipeline : with_job_ ? &job : nullptr;
    deps.arm = arm;
    deps.estop = estop;
    PETRA_TRY(exec_.init(*config, deps));
    PETRA_TRY(sender_.open("127.0.0.1", 0));
    return sender_.set_peer("127.0.0.1", exec_.command_port());
  }

  std::vector<std::uint8_t> packet(const cmd::Command& c) const {
    cmd::AuthKey key = *cmd::parse_key_hex(std::span<const char>(key_hex_.data(), 64));
    std::vector<std::uint8_t> out(cmd::kMaxCommandBytes);
    auto n = cmd::encode_command_packet(c, 0, key, out);
    EXPECT_TRUE(n.ok());
    out.resize(n.ok() ? *n : 0);
    return out;
  }
  cmd::Command make(cmd::FunctionCode code, cmd::Args args) { return {code, ++counter, args}; }
  cmd::Command make(cmd::FunctionCode code) { return make(code, cmd::default_args(code)); }

  // A new uplink key (64 hex digits) for the next boot and for signing.
  void set_key(const std::string& hex) {
    key_hex_ = hex;
    std::ofstream(dir_ / "key.hex") << hex << "\n";
  }

  void send_raw(const std::vector<std::uint8_t>& bytes) { sender_.send(bytes); }
  void send(const cmd::Command& c) { send_raw(packet(c)); }

  // Runs cycles (no sleeping: the test drives the loop) and collects telemetry.
  void cycles(int n) {
    for (int i = 0; i < n; ++i) {
      exec_.run_cycle();
      drain();
    }
  }
  // Cycles until pred() holds or max cycles (10 ms sleep each) pass.
  template <class Pred>
  bool cycle_until(Pred pred, int max = 500) {
    for (int i = 0; i < max; ++i) {
      cycles(1);
      if (pred()) return true;
      usleep(2000);
    }
    return false;
  }
  void drain() {
    std::uint8_t buf[2048];
    for (;;) {
      auto n = ground_.receive(buf);
      if (!n || !n->got) return;
      auto p = tlm::decode_tm(std::span<const std::uint8_t>(buf, n->size));
      EXPECT_TRUE(p.ok()) << p.error().message;
      if (p.ok()) received.push_back(*p);
    }
  }

  template <class T>
  std::vector<T> all() const {
    std::vector<T> out;
    for (const auto& p : received)
      if (const T* t = std::get_if<T>(&p.body)) out.push_back(*t);
    return out;
  }
  std::vector<tlm::Ack> acks_for(std::uint32_t which) const {
    std::vector<tlm::Ack> out;
    for (const auto& a : all<tlm::Ack>())
      if (a.counter == which) out.push_back(a);
    return out;
  }
  bool has_event(std::uint16_t id) const {
    for (const auto& e : all<tlm::Event>())
      if (e.event_id == id) return true;
    return false;
  }
  bool has_ack(std::uint32_t which, AckStage stage) const {
    for (const auto& a : acks_for(which))
      if (a.stage == static_cast<std::uint8_t>(stage)) return true;
    return false;
  }

  fsw::Executive& exec() { return exec_; }
  const std::filesystem::path& dir() const { return dir_; }
  void keep_dir() { keep_dir_ = true; }

  ScriptedPipelineJob job;
  fsw::PipelineJob* pipeline = nullptr;  // optional: replaces the scripted job (set before boot())
  std::string budget;           // optional: the config's budget object instead of the small one
  fsw::ArmPort* arm = nullptr;  // optional, set before boot()
  hal::DigitalInput* estop = nullptr;   // optional, set before boot()
  hal::StereoCamera* camera = nullptr;  // optional: replaces the file camera (set before boot())
  std::uint32_t counter = 0;
  std::size_t queue_packets = 256;
  std::string loop = R"({"cycle_ms":10})";
  std::string counter_file = "counter.txt";  // "": the configuration names none (beside the key)
  std::string uplink_extra;                  // more "uplink" members, e.g. R"(,"counter_floor":0)"
  std::vector<tlm::TmPacket> received;
  hal::UdpLink ground_;  // telemetry receiver

 private:
  static int next_id() {
    static int id = 0;
    return ++id;
  }
  bool with_job_;
  bool keep_dir_ = false;
  std::string extra_;
  std::filesystem::path dir_;
  std::string key_hex_ = kKeyHex;
  hal::SystemClock clock_;
  hal::FileStereoCamera camera_;
  fsw::Executive exec_;
  hal::UdpLink sender_;
};

inline cmd::SelectRoiArgs roi(int x, int y, int w, int h, int c) {
  cmd::SelectRoiArgs a;
  a.x_px = static_cast<std::uint16_t>(x);
  a.y_px = static_cast<std::uint16_t>(y);
  a.w_px = static_cast<std::uint16_t>(w);
  a.h_px = static_cast<std::uint16_t>(h);
  a.planes = static_cast<std::uint8_t>(c);
  return a;
}

}  // namespace petra::test
