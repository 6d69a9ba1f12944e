// Ground side of the downlink: telemetry packets as readable lines or JSON
// lines (`petra tlm`), with names for modes, reasons, function codes,
// parameters and event texts taken from the packet definitions.
#pragma once

#include <string>

#include "tlm/telemetry.hpp"

namespace petra::ground {

// missing_before: packets of this APID lost just before this one (SeqTracker);
// shown only when non-zero.
std::string format_line(const tlm::TmPacket& p, std::uint32_t missing_before = 0);
// One JSON object: {"apid":..,"packet":"NAME","seq":..,"time":..,"fields":{...}}
// (PRODUCT data bytes as a hex string), plus "missing_before":N after "seq"
// when packets of this APID were lost just before this one.
std::string format_json(const tlm::TmPacket& p, std::uint32_t missing_before = 0);
// An event's text with its arguments filled in.
std::string event_text(const tlm::Event& e);

}  // namespace petra::ground
