// `petra cmd NAME [field=value ...]`: builds a telecommand from the packet
// definitions, signs it with the uplink key (HMAC-SHA256, next counter from
// the counter file) and sends it over UDP. With --wait it listens on the
// telemetry port for the command's acknowledgements and prints them.
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "algo/wire/reasons.hpp"
#include "cmd/command_packet.hpp"
#include "hal/udp_link.hpp"
#include "sim/cli/commands.hpp"
#include "sim/ground/command_builder.hpp"
#include "sim/ground/tlm_format.hpp"

namespace petra::cli {

void add_cmd(CLI::App& app, Outcome& outcome) {
  auto* sub = app.add_subcommand("cmd", "Build, sign and send a telecommand");
  sub->footer("Commands and fields (docs/icd.md):\n" + ground::command_usage());
  static std::string name;
  static std::vector<std::string> words;
  static std::string key_path = "petra.key";
  static std::string counter_path;
  static std::string host = "127.0.0.1";
  static int port = 47100;
  static long counter = -1;
  static bool wait = false;
  static int tlm_port = 47101;
  static int timeout_ms = 3000;
  sub->add_option("name", name, "command name, e.g. SELECT_ROI")->required();
  sub->add_option("fields", words, "field=value ...");
  sub->add_option("--key", key_path, "uplink key file (64 hex digits)")->capture_default_str();
  sub->add_option("--counter-file", counter_path, "last counter used (default: KEY.counter)");
  sub->add_option("--counter", counter, "use this counter instead of the counter file");
  sub->add_option("--host", host, "petra-fsw command address")->capture_default_str();
  sub->add_option("--port", port, "petra-fsw command port")->capture_default_str();
  sub->add_flag("--wait", wait, "wait for the acknowledgements on the telemetry port");
  sub->add_option("--tlm-port", tlm_port, "telemetry port for --wait")->capture_default_str();
  sub->add_option("--timeout-ms", timeout_ms, "how long --wait waits")->capture_default_str();
  sub->callback([&outcome] {
    auto command = ground::build_command(name, words);
    if (!command) {
      outcome.exit_code = fail("cmd", command.error().message);
      return;
    }
    if (auto s = cmd::auth_init(); !s) {
      outcome.exit_code = fail("cmd", s.error().message);
      return;
    }
    auto key = ground::load_uplink_key(key_path);
    if (!key) {
      outcome.exit_code = fail("cmd", key.error().message);
      return;
    }
    if (counter >= 0) {
      command->counter = static_cast<std::uint32_t>(counter);
    } else {
      auto next = ground::next_counter(counter_path.empty() ? key_path + ".counter" : counter_path);
      if (!next) {
        outcome.exit_code = fail("cmd", next.error().message);
        return;
      }
      command->counter = *next;
    }
    std::vector<std::uint8_t> packet(cmd::kMaxCommandBytes);
    auto n = cmd::encode_command_packet(
        *command, static_cast<std::uint16_t>(command->counter & 0x3FFF), *key, packet);
    if (!n) {
      outcome.exit_code = fail("cmd", n.error().message);
      return;
    }
    hal::UdpLink tlm;
    if (wait) {
      if (auto s = tlm.open("0.0.0.0", static_cast<std::uint16_t>(tlm_port)); !s) {
        outcome.exit_code = fail("cmd", s.error().message);
        return;
      }
    }
    hal::UdpLink link;
    Status s = link.open("0.0.0.0", 0);
    if (s) s = link.set_peer(host.c_str(), static_cast<std::uint16_t>(port));
    if (!s || link.send(std::span(packet).first(*n)) != hal::SendResult::sent) {
      outcome.exit_code = fail("cmd", s ? "send failed" : s.error().message);
      return;
    }
    const cmd::CommandDesc* d = cmd::find_command(static_cast<std::uint8_t>(command->code));
    std::printf("sent %s counter %u (%zu bytes) to %s:%d\n", d->name, command->counter, *n,
                host.c_str(), port);
    if (!wait) return;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    std::vector<std::uint8_t> buf(4096);
    bool final_seen = false;
    while (!final_seen && std::chrono::steady_clock::now() < deadline) {
      auto got = tlm.receive_wait(buf, 50);
      if (!got || !got->got) continue;
      auto p = tlm::decode_tm(std::span(buf).first(std::min(got->size, buf.size())));
      if (!p) continue;
      const auto* ack = std::get_if<tlm::Ack>(&p->body);
      if (ack == nullptr || ack->counter != command->counter) continue;
      std::printf("%s\n", ground::format_line(*p).c_str());
      const auto stage = static_cast<AckStage>(ack->stage);
      final_seen = stage != AckStage::ACCEPTED;
      if (stage == AckStage::REJECTED || stage == AckStage::FAILED) outcome.exit_code = 3;
    }
    if (!final_seen) outcome.exit_code = fail("cmd", "no final acknowledgement before the timeout");
  });
}

}  // namespace petra::cli
