// Ground side of "no telemetry packet lost without a visible gap or counter":
// follows each APID's 14-bit sequence count (the flight queue spends a count
// on every packet it makes, dropped or not) and counts the packets missing
// between two received ones, plus the flight's own drop counter from
// housekeeping (HK tlm_dropped) and the datagrams that failed verification.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "tlm/telemetry.hpp"

namespace petra::ground {

struct ApidStats {
  std::uint64_t received = 0;
  std::uint64_t missing = 0;   // packets never received between two that were
  std::uint64_t gaps = 0;      // how many times a run of packets went missing
  std::uint64_t restarts = 0;  // count went backwards (the service restarted)
  std::uint16_t last_seq = 0;
};

class SeqTracker {
 public:
  // Records one verified packet; returns how many packets of its APID went
  // missing just before it (0 when none, or for the first one seen).
  std::uint32_t observe(const tlm::TmPacket& p);
  // A datagram that failed verification (length, CRC, APID...).
  void bad_datagram() { ++bad_; }

  const std::map<std::uint16_t, ApidStats>& apids() const { return apids_; }
  std::uint64_t missing() const;
  std::uint64_t bad() const { return bad_; }
  // The latest HK tlm_dropped (-1 before any housekeeping arrived).
  std::int64_t flight_dropped() const { return flight_dropped_; }

  // "summary: 120 packets, 3 missing in 2 gaps (EVENT 3), 0 bad, flight dropped 3"
  std::string summary_line() const;
  // {"summary":{"packets":..,"missing":..,"bad":..,"flight_dropped":..,"apids":[...]}}
  std::string summary_json() const;

 private:
  std::map<std::uint16_t, ApidStats> apids_;
  std::uint64_t bad_ = 0;
  std::int64_t flight_dropped_ = -1;
};

}  // namespace petra::ground
