// Ground side of the downlink: telemetry packets as readable lines or JSON
// lines (`petra tlm`), with names for modes, reasons, function codes,
// parameters and event texts taken from the packet definitions.
#pragma once

#include <string>

#include "tlm/telemetry.hpp"

namespace petra::ground {

std::string format_line(const tlm::TmPacket& p);
// One JSON object: {"apid":..,"packet":"NAME","seq":..,"time":..,"fields":{...}}
// (PRODUCT data bytes as a hex string).
std::string format_json(const tlm::TmPacket& p);
// An event's text with its arguments filled in.
std::string event_text(const tlm::Event& e);

}  // namespace petra::ground
