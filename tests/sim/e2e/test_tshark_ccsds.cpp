// Wireshark's CCSDS dissector reads our primary headers as we meant them:
// packets from the real encoders are written into a pcap file (no capture
// privileges needed) and `tshark -d udp.port==PORT,ccsds` decodes them.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cmd/command_packet.hpp"
#include "tlm/telemetry.hpp"

namespace petra {
namespace {

constexpr std::uint16_t kTlmPort = 47101;
constexpr std::uint16_t kCmdPort = 47100;

void put16(std::vector<std::uint8_t>& v, unsigned x) {
  v.push_back(static_cast<std::uint8_t>(x >> 8));
  v.push_back(static_cast<std::uint8_t>(x));
}
void put32le(std::ofstream& f, std::uint32_t x) {
  for (int i = 0; i < 4; ++i) f.put(static_cast<char>((x >> (8 * i)) & 0xFF));
}

// Ethernet + IPv4 + UDP around one payload, 127.0.0.1 -> 127.0.0.1.
std::vector<std::uint8_t> frame(const std::vector<std::uint8_t>& payload, std::uint16_t dport) {
  std::vector<std::uint8_t> f(12, 0);
  put16(f, 0x0800);
  const std::size_t ip_at = f.size();
  const unsigned ip_len = 20 + 8 + static_cast<unsigned>(payload.size());
  const std::uint8_t ip[20] = {0x45,
                               0,
                               static_cast<std::uint8_t>(ip_len >> 8),
                               static_cast<std::uint8_t>(ip_len),
                               0,
                               0,
                               0x40,
                               0,
                               64,
                               17,
                               0,
                               0,
                               127,
                               0,
                               0,
                               1,
                               127,
                               0,
                               0,
                               1};
  f.insert(f.end(), ip, ip + 20);
  unsigned sum = 0;
  for (int i = 0; i < 20; i += 2) sum += (unsigned{f[ip_at + i]} << 8) | f[ip_at + i + 1];
  while (sum >> 16) sum = (sum & 0xFFFF) + (sum >> 16);
  f[ip_at + 10] = static_cast<std::uint8_t>(~sum >> 8);
  f[ip_at + 11] = static_cast<std::uint8_t>(~sum);
  put16(f, 40000);
  put16(f, dport);
  put16(f, 8 + static_cast<unsigned>(payload.size()));
  put16(f, 0);  // no UDP checksum (allowed for IPv4)
  f.insert(f.end(), payload.begin(), payload.end());
  return f;
}

struct Sent {
  std::vector<std::uint8_t> bytes;
  std::uint16_t port;
};

TEST(TsharkCcsds, DissectorDecodesOurPrimaryHeaders) {
  if (std::system("command -v tshark >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "tshark not installed (toolchain/packages-test.txt lists it)";
  std::vector<Sent> sent;
  auto add_tm = [&](const auto& packet, std::uint16_t seq, wire::SeqFlags flags) {
    std::vector<std::uint8_t> b(tlm::kMaxTmBytes);
    b.resize(tlm::encode_tm(packet, seq, flags, tlm::TmTime{1700000000, 5}, b));
    sent.push_back({b, kTlmPort});
  };
  tlm::Housekeeping hk;
  hk.mode = 1;
  add_tm(hk, 17, wire::SeqFlags::unsegmented);
  tlm::Event ev;
  ev.event_id = 2;
  add_tm(ev, 16383, wire::SeqFlags::unsegmented);
  tlm::Ack ack;
  ack.stage = 1;
  add_tm(ack, 1, wire::SeqFlags::unsegmented);
  tlm::Product chunk;
  chunk.chunks = 3;
  add_tm(chunk, 100, wire::SeqFlags::first);
  chunk.chunk = 1;
  add_tm(chunk, 101, wire::SeqFlags::continuation);
  chunk.chunk = 2;
  add_tm(chunk, 102, wire::SeqFlags::last);
  cmd::AuthKey key;
  cmd::SelectRoiArgs roi;
  roi.w_px = 100;
  std::vector<std::uint8_t> tc(cmd::kMaxCommandBytes);
  tc.resize(*cmd::encode_command_packet(cmd::Command{cmd::FunctionCode::SELECT_ROI, 9, roi}, 1234,
                                        key, tc));
  sent.push_back({tc, kCmdPort});

  const auto dir = std::filesystem::temp_directory_path();
  const auto pcap = dir / ("petra_ccsds_" + std::to_string(::getpid()) + ".pcap");
  {
    std::ofstream f(pcap, std::ios::binary);
    put32le(f, 0xa1b2c3d4);
    f.put(2).put(0).put(4).put(0);  // version 2.4
    put32le(f, 0);
    put32le(f, 0);
    put32le(f, 65535);
    put32le(f, 1);  // Ethernet
    std::uint32_t t = 0;
    for (const Sent& s : sent) {
      const auto fr = frame(s.bytes, s.port);
      put32le(f, 1700000000 + t++);
      put32le(f, 0);
      put32le(f, static_cast<std::uint32_t>(fr.size()));
      put32le(f, static_cast<std::uint32_t>(fr.size()));
      f.write(reinterpret_cast<const char*>(fr.data()), static_cast<std::streamsize>(fr.size()));
    }
  }
  const auto out = dir / ("petra_ccsds_" + std::to_string(::getpid()) + ".txt");
  const std::string cmdline = "tshark -r " + pcap.string() +
                              " -d udp.port==" + std::to_string(kTlmPort) +
                              ",ccsds -d udp.port==" + std::to_string(kCmdPort) +
                              ",ccsds -T fields -E separator=, -e ccsds.version -e ccsds.type -e "
                              "ccsds.secheader -e ccsds.apid "
                              "-e ccsds.seqflag -e ccsds.seqnum -e ccsds.length > " +
                              out.string() + " 2>/dev/null";
  ASSERT_EQ(std::system(cmdline.c_str()), 0) << cmdline;
  std::ifstream in(out);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), sent.size());
  for (std::size_t i = 0; i < sent.size(); ++i) {
    const wire::PrimaryHeader h = wire::read_primary_header(sent[i].bytes);
    std::ostringstream want;
    want << unsigned{h.version} << "," << static_cast<unsigned>(h.type) << ","
         << (h.secondary_header ? "1" : "0") << "," << h.apid << ","
         << static_cast<unsigned>(h.seq_flags) << "," << h.seq_count << "," << h.data_length;
    // tshark prints booleans as True/False or 1/0 depending on version: normalise.
    std::string got = lines[i];
    for (const char* t : {"True", "true"})
      if (auto p = got.find(t); p != std::string::npos) got.replace(p, std::string(t).size(), "1");
    EXPECT_EQ(got, want.str()) << "packet " << i;
  }
  std::printf(
      "[ figures  ] tshark decoded %zu CCSDS primary headers (TM APIDs 0x010-0x030, TC 0x064)\n",
      lines.size());
  std::filesystem::remove(pcap);
  std::filesystem::remove(out);
}

}  // namespace
}  // namespace petra
