// `petra archive query|replay`: the ground's telemetry archive (SQLite, filled
// by `petra gnd serve --archive FILE`; sim/ground/tlm_archive.hpp). query
// prints the stored packets (lines, JSON lines, CSV or counts per APID) by
// time range, APID and event severity; replay sends a stored pass's raw
// packets again over UDP, e.g. into a station (docs/ops.md "Telemetry archive").
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>

#include "hal/udp_link.hpp"
#include "sim/cli/commands.hpp"
#include "sim/ground/tlm_archive.hpp"
#include "sim/ground/tlm_format.hpp"
#include "tlm/event_defs.hpp"

namespace petra::cli {

namespace {

struct Filters {
  std::string db;
  double from_s = -1e300, to_s = 1e300;
  bool receive_time = false;
  std::string apid, severity;
  long limit = -1;
};

void add_filters(CLI::App* sub, Filters& f) {
  sub->add_option("--db", f.db, "archive file")->required();
  sub->add_option("--from", f.from_s, "first time, s (spacecraft time unless --receive-time)");
  sub->add_option("--to", f.to_s, "last time, s");
  sub->add_flag("--receive-time", f.receive_time, "--from/--to are ground receive times (UNIX s)");
  sub->add_option("--apid", f.apid, "one packet kind: APID number or name (HK, EVENT, ACK, ...)");
  sub->add_option("--min-severity", f.severity,
                  "events of this severity or above only: DEBUG, INFO, WARNING, ERROR, FATAL");
  sub->add_option("--limit", f.limit, "at most this many packets");
}

// The filters as a query; the error names the option.
Result<ground::ArchiveQuery> to_query(const Filters& f) {
  ground::ArchiveQuery q;
  q.from_s = f.from_s;
  q.to_s = f.to_s;
  q.by_receive_time = f.receive_time;
  q.limit = f.limit;
  if (!f.apid.empty()) {
    for (int a = 0; a < 2048 && q.apid < 0; ++a)
      if (const tlm::TmDesc* d = tlm::find_telemetry(static_cast<std::uint16_t>(a));
          d != nullptr && (f.apid == d->name || f.apid == std::to_string(a)))
        q.apid = a;
    if (q.apid < 0)
      return Error::make(Errc::invalid_argument, "--apid %s: no such telemetry packet",
                         f.apid.c_str());
  }
  if (!f.severity.empty()) {
    for (int s = 0; s <= 4 && q.min_severity < 0; ++s)
      if (f.severity == severity_name(static_cast<Severity>(s)) || f.severity == std::to_string(s))
        q.min_severity = s;
    if (q.min_severity < 0)
      return Error::make(Errc::invalid_argument,
                         "--min-severity %s: expected DEBUG, INFO, WARNING, ERROR or FATAL",
                         f.severity.c_str());
  }
  return q;
}

// Opens the archive and turns the filters into a query, or reports why not.
std::unique_ptr<ground::TlmArchive> open_for(const char* cmd, const Filters& f,
                                             ground::ArchiveQuery& q, Outcome& outcome) {
  auto query = to_query(f);
  if (!query) {
    outcome.exit_code = fail(cmd, query.error().message);
    return nullptr;
  }
  q = *query;
  if (!std::filesystem::exists(f.db)) {
    outcome.exit_code = fail(cmd, (f.db + ": No such file or directory").c_str());
    return nullptr;
  }
  auto a = ground::TlmArchive::open(f.db);
  if (!a) {
    outcome.exit_code = fail(cmd, a.error().message);
    return nullptr;
  }
  return std::move(*a);
}

void add_query(CLI::App* archive, Outcome& outcome) {
  auto* sub = archive->add_subcommand("query", "Print stored packets (lines, JSON, CSV, counts)");
  static Filters f;
  static bool json = false, csv = false, count = false;
  add_filters(sub, f);
  sub->add_flag("--json", json, "one JSON object per line (as petra tlm --json)");
  sub->add_flag("--csv", csv, "CSV: receive_s, scet_s, apid, packet, seq, severity, decoded");
  sub->add_flag("--count", count, "packets per APID only");
  sub->callback([&outcome] {
    ground::ArchiveQuery q;
    auto a = open_for("archive query", f, q, outcome);
    if (!a) return;
    Status s;
    if (count) {
      auto counts = a->count_by_apid(q);
      if (counts)
        for (const auto& [apid, n] : *counts) {
          const tlm::TmDesc* d = tlm::find_telemetry(static_cast<std::uint16_t>(apid));
          std::printf("%-12s apid %3d  %ld packets\n", d != nullptr ? d->name : "?", apid, n);
        }
      s = counts ? Status{} : Status(counts.error());
    } else if (csv) {
      s = a->export_csv(q, stdout);
    } else {
      s = a->query(q, [](const ground::ArchivedPacket& p) {
        if (json) {
          std::printf("%s\n", p.decoded.c_str());
          return;
        }
        auto decoded = tlm::decode_tm(p.raw);
        std::printf("%.6f %s\n", p.receive_s,
                    decoded ? ground::format_line(*decoded).c_str() : "(undecodable)");
      });
    }
    if (!s) outcome.exit_code = fail("archive query", s.error().message);
  });
}

void add_replay(CLI::App* archive, Outcome& outcome) {
  auto* sub = archive->add_subcommand(
      "replay", "Send a stored pass's raw packets again over UDP (e.g. into petra gnd serve)");
  static Filters f;
  static std::string host = "127.0.0.1";
  static int port = 47101;
  static double speed = 1.0;
  add_filters(sub, f);
  sub->add_option("--host", host, "destination address")->capture_default_str();
  sub->add_option("--port", port, "destination port (the station's --tlm-port)")
      ->capture_default_str();
  sub->add_option("--speed", speed, "1: as received; 10: ten times faster; 0: no pauses")
      ->capture_default_str();
  sub->callback([&outcome] {
    if (speed < 0 || port < 1 || port > 65535) {
      outcome.exit_code = fail("archive replay", "--speed must be >= 0, --port 1..65535");
      return;
    }
    ground::ArchiveQuery q;
    auto a = open_for("archive replay", f, q, outcome);
    if (!a) return;
    hal::UdpLink link;
    Status s = link.open("0.0.0.0", 0);
    if (s) s = link.set_peer(host.c_str(), static_cast<std::uint16_t>(port));
    if (!s) {
      outcome.exit_code = fail("archive replay", s.error().message);
      return;
    }
    link.set_send_buffer(4 << 20);
    long sent = 0, failed = 0;
    double first_s = -1;
    const auto start = std::chrono::steady_clock::now();
    s = a->query(q, [&](const ground::ArchivedPacket& p) {
      if (first_s < 0) first_s = p.receive_s;
      if (speed > 0)
        std::this_thread::sleep_until(
            start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                        std::chrono::duration<double>((p.receive_s - first_s) / speed)));
      else if (sent % 64 == 63)
        std::this_thread::sleep_for(std::chrono::milliseconds(2));  // the receiver keeps up
      if (link.send(p.raw) == hal::SendResult::sent)
        ++sent;
      else
        ++failed;
    });
    if (!s) {
      outcome.exit_code = fail("archive replay", s.error().message);
      return;
    }
    std::printf("replayed %ld packets to %s:%d%s\n", sent, host.c_str(), port,
                failed ? (", " + std::to_string(failed) + " could not be sent").c_str() : "");
    if (failed) outcome.exit_code = fail("archive replay", "some packets could not be sent");
  });
}

}  // namespace

void add_archive(CLI::App& app, Outcome& outcome) {
  auto* archive = app.add_subcommand("archive", "The ground's telemetry archive (SQLite)");
  archive->require_subcommand(1);
  add_query(archive, outcome);
  add_replay(archive, outcome);
}

}  // namespace petra::cli
