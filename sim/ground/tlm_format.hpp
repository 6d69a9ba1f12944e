// Ground side of the downlink: telemetry packets as readable lines or JSON
// lines (`petra tlm`), with names for modes, reasons, function codes,
// parameters and event texts taken from the packet definitions.
#pragma once

#include <cstdint>
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
// An event's text with its arguments filled in (a rejection's detail named).
std::string event_text(const tlm::Event& e);
// A refusal's detail in the operator's words: "field planes", "in mode SAFE",
// "unknown parameter id 99" ("" when there is nothing to say). The detail's
// meaning depends on the reason (algo/wire/reasons.hpp).
std::string refusal_detail(std::uint8_t function_code, std::uint8_t reason, std::uint16_t detail);

}  // namespace petra::ground
