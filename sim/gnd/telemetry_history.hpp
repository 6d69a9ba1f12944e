// The ground station's telemetry for Open MCT (sim/gnd/web/openmct): the
// dictionary of every telemetry point, generated from the packet definitions
// (tlm/tlm_defs.hpp, the same lists as docs/icd.md and the XTCE), and the
// history of one point or one packet kind read back from the archive.
//   GET /api/dictionary
//     {"packets":[{"name":"HK","apid":16,"description":..,
//                  "points":[{"key":"uptime_s","unit":"s","min":..,"max":..,"description":..}]}]}
//     (array fields as one point per element, "joint_deg[2]"; PRODUCT left out)
//   GET /api/history?packet=HK&field=uptime_s&start=MS&end=MS
//     [{"t":MS,"v":value},...] in spacecraft time (ms since 1970)
//   GET /api/history?packet=EVENT&start=MS&end=MS[&min_severity=N]  (no field: whole packets)
//     [{"t":MS,"fields":{...},"names":{...},"line":"..."},...]
//   GET /api/gaps?start=MS&end=MS
//     [{"t":MS,"packet":"EVENT","apid":17,"seq":42,"missing":3},...]: every packet
//     with packets of its APID missing just before it, in receive order (the
//     first packet of each APID in the range has no known predecessor: no gap)
#pragma once

#include <string>

#include "algo/core/result.hpp"

namespace petra::gnd {

std::string dictionary_json();

struct HistoryRequest {
  std::string packet;  // name: HK, EVENT, ACK, ...
  std::string field;   // "" for whole packets
  double start_ms = 0, end_ms = 0;
  int min_severity = -1;  // EVENT only
  long limit = 20000;
};

// Reads the archive at `archive_path` (a second connection beside the
// station's writer). Errors name the parameter or the file.
Result<std::string> history_json(const std::string& archive_path, const HistoryRequest& r);

// The sequence gaps of every APID in the archive between two spacecraft times.
Result<std::string> gaps_json(const std::string& archive_path, double start_ms, double end_ms);

}  // namespace petra::gnd
