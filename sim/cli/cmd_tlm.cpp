// `petra tlm [--follow] [--json]`: receives telemetry on the UDP port,
// verifies each packet (length, CRC, known APID, size) and prints it as a
// readable line or a JSON line. Bad packets are reported on stderr and
// skipped. --save-products DIR reassembles and writes images and clouds.
// Each APID's sequence count is followed: a packet after a gap says how many
// went missing, and on exit (timeout, --count, SIGINT or SIGTERM) a summary
// line (JSON object with --json) gives packets, gaps, bad datagrams and the
// flight's own drop counter per APID.
#include <chrono>
#include <csignal>
#include <cstdio>
#include <string>
#include <vector>

#include "hal/udp_link.hpp"
#include "sim/cli/commands.hpp"
#include "sim/ground/product_assembler.hpp"
#include "sim/ground/seq_tracker.hpp"
#include "sim/ground/tlm_format.hpp"

namespace petra::cli {

namespace {
volatile std::sig_atomic_t g_tlm_stop = 0;
extern "C" void on_stop_signal(int) {
  g_tlm_stop = 1;
}
}  // namespace

void add_tlm(CLI::App& app, Outcome& outcome) {
  auto* sub = app.add_subcommand("tlm", "Receive, verify and decode telemetry");
  static std::string host = "0.0.0.0";
  static int port = 47101;
  static bool follow = false;
  static bool json = false;
  static int timeout_ms = 2000;
  static long count = 0;
  static bool quiet_products = false;
  static std::string save_dir;
  sub->add_option("--host", host, "local address to listen on")->capture_default_str();
  sub->add_option("--port", port, "telemetry port")->capture_default_str();
  sub->add_flag("--follow,-f", follow, "keep receiving until interrupted");
  sub->add_flag("--json", json, "one JSON object per line");
  sub->add_option("--timeout-ms", timeout_ms,
                  "without --follow: stop after this long without packets")
      ->capture_default_str();
  sub->add_option("--count", count, "stop after this many packets");
  sub->add_flag("--no-product-chunks", quiet_products, "do not print PRODUCT chunks");
  sub->add_option("--save-products", save_dir, "write completed products into this folder");
  sub->callback([&outcome] {
    hal::UdpLink link;
    if (auto s = link.open(host.c_str(), static_cast<std::uint16_t>(port)); !s) {
      outcome.exit_code = fail("tlm", s.error().message);
      return;
    }
    ground::ProductAssembler assembler;
    ground::SeqTracker seqs;
    std::signal(SIGINT, on_stop_signal);
    std::signal(SIGTERM, on_stop_signal);
    const auto summary = [&seqs] {
      std::printf("%s\n", (json ? seqs.summary_json() : seqs.summary_line()).c_str());
      std::fflush(stdout);
    };
    std::vector<std::uint8_t> buf(70000);
    long seen = 0;
    auto idle_since = std::chrono::steady_clock::now();
    for (;;) {
      if (g_tlm_stop != 0) return summary();
      auto n = link.receive_wait(buf, 100);
      if (!n) {
        if (g_tlm_stop != 0) return summary();  // the signal interrupted the wait
        outcome.exit_code = fail("tlm", n.error().message);
        return;
      }
      if (!n->got) {
        if (!follow &&
            std::chrono::steady_clock::now() - idle_since > std::chrono::milliseconds(timeout_ms))
          return summary();
        continue;
      }
      idle_since = std::chrono::steady_clock::now();
      auto p = tlm::decode_tm(std::span(buf).first(std::min(n->size, buf.size())));
      if (!p) {
        seqs.bad_datagram();
        std::fprintf(stderr, "petra tlm: dropped a packet: %s\n", p.error().message);
        continue;
      }
      const std::uint32_t missing = seqs.observe(*p);
      const auto* chunk = std::get_if<tlm::Product>(&p->body);
      if (chunk != nullptr && !save_dir.empty())
        if (auto done = assembler.add(*chunk)) {
          const std::string path = ground::write_product(*done, save_dir);
          std::fprintf(stderr, "petra tlm: wrote %s\n", path.c_str());
        }
      if (chunk == nullptr || !quiet_products) {
        std::printf(
            "%s\n",
            (json ? ground::format_json(*p, missing) : ground::format_line(*p, missing)).c_str());
        std::fflush(stdout);
      }
      if (count > 0 && ++seen >= count) return summary();
    }
  });
}

}  // namespace petra::cli
