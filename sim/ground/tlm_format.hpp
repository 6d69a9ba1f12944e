// Ground side of the downlink: telemetry packets as readable lines or JSON
// lines (`petra tlm`), with names for modes, reasons, function codes,
// parameters and event texts taken from the packet definitions.
#pragma once

#include <cstdint>
#include <string>

#include "tlm/telemetry.hpp"

namespace petra::ground {

std::string format_line(const tlm::TmPacket& p);
// One JSON object: {"apid":..,"packet":"NAME","seq":..,"time":..,"fields":{...}}
// (PRODUCT data bytes as a hex string).
std::string format_json(const tlm::TmPacket& p);
// An event's text with its arguments filled in (a rejection's detail named).
std::string event_text(const tlm::Event& e);
// A refusal's detail in the operator's words: "field planes", "in mode SAFE",
// "unknown parameter id 99" ("" when there is nothing to say). The detail's
// meaning depends on the reason (cmd/reasons.hpp).
std::string refusal_detail(std::uint8_t function_code, std::uint8_t reason, std::uint16_t detail);

}  // namespace petra::ground
