// What `petra demo` shows once the grind planes arrive: a readable table of
// the planes, the ground and the statistics received as telemetry, the same
// planes as planes.json (contract format), and their score against the
// scene's truth.json with the project's scorer (sim/score).
#pragma once

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "tlm/telemetry.hpp"

namespace petra::demo {

struct Received {
  std::optional<tlm::EvalResult> result;
  std::optional<tlm::GroundPlane> ground;
  std::vector<tlm::GrindPlane> planes;  // as received
};

// Planes sorted by rank; table, ground, statistics and step times.
void print_received(const Received& r, std::FILE* out);
// planes.json text (docs/icd.md) from the telemetry.
std::string planes_json(const Received& r);

// True when two planes.json texts hold the same planes and ground, value for
// value (both are written with round-trip precision).
bool same_planes(const std::string& a, const std::string& b);

// Limits the demo holds the planes to (printed with the verdict).
struct DemoLimits {
  double max_normal_deg = 5.0;
  double max_centroid_mm = 2.0;
};

// Scores planes.json against truth.json, prints the scorer's table and a
// one-line verdict; true when every limit is met.
bool score_and_print(const std::string& truth_json, const std::string& planes_json_text,
                     const DemoLimits& limits, std::FILE* out);

}  // namespace petra::demo
