// The parameter table: every tunable the ground can read (GET_PARAM,
// DUMP_PARAMS) and change (SET_PARAM). Values travel as f64; `integer` ones
// must be whole numbers. Defaults here are overridden at boot by the defaults
// file named in the configuration (docs/executive.md).
// X(NAME, id, unit, min, max, default, integer, "meaning")
#pragma once

#include <cstdint>
#include <span>

#include "algo/core/chain_defaults.hpp"

#define PETRA_PARAMS(X)                                                                           \
  X(HK_PERIOD_MS, 1, "ms", 100, 60000, 1000, true, "housekeeping packet period")                  \
  X(MATCH_METHOD, 2, "enum", 0, 1, 0, true, "stereo matcher: 0 dynamic programming, 1 graph cut") \
  X(DISP_MIN_PX, 3, "px", 0, 1023, kEnvelopeMinPx, true, "disparity envelope searched: smallest") \
  X(DISP_MAX_PX, 4, "px", 0, 1023, kEnvelopeMaxPx, true, "disparity envelope searched: largest")  \
  X(SHADOW_FRACTION, 5, "1", 0, 0.9, kShadowFraction, false,                                      \
    "expected fraction of shadow pixels in the ROI")                                              \
  X(MIN_PLANE_AREA_MM2, 6, "mm2", 0, 1e6, 100, false,                                             \
    "grind planes smaller than this are refused")                                                 \
  X(PRODUCT_CHUNKS_PER_CYCLE, 7, "1", 1, 64, 8, true, "product packets queued per loop cycle")    \
  X(THUMB_DECIMATION, 8, "1", 1, 16, 4, true, "thumbnail = image subsampled by this factor")      \
  X(SEND_LEFT_IMAGE, 9, "bool", 0, 1, 1, true, "downlink the left image after each acquisition")  \
  X(LEFT_IMAGE_DECIMATION, 10, "1", 1, 16, 1, true, "downlinked left image subsampling factor")   \
  X(CLOUD_MAX_POINTS, 11, "1", 0, 65535, 4096, true,                                              \
    "point cloud product: at most this many points")                                              \
  X(HEARTBEAT_TIMEOUT_MS, 12, "ms", 100, 600000, 5000, true,                                      \
    "a component silent this long is a fault (SAFE)")                                             \
  X(EVAL_TIMEOUT_S, 13, "s", 1, 3600, 600, true, "an evaluation running longer is aborted (fault)")

namespace petra {

enum class ParamId : std::uint16_t {
#define PETRA_PARAM_ENUM(NAME, id, unit, lo, hi, def, integer, desc) NAME = (id),
  PETRA_PARAMS(PETRA_PARAM_ENUM)
#undef PETRA_PARAM_ENUM
};

struct ParamDesc {  // pointers, doubles, then the small fields: no padding between
  const char* name;
  const char* unit;
  const char* description;
  double min;
  double max;
  double default_value;
  std::uint16_t id;
  bool integer;
};

inline constexpr ParamDesc kParamTable[] = {
#define PETRA_PARAM_DESC(NAME, id, unit, lo, hi, def, integer, desc) \
  ParamDesc{#NAME, unit, desc, lo, hi, def, id, integer},
    PETRA_PARAMS(PETRA_PARAM_DESC)
#undef PETRA_PARAM_DESC
};

inline constexpr std::size_t kParamCount = sizeof(kParamTable) / sizeof(kParamTable[0]);

constexpr std::span<const ParamDesc> param_table() {
  return {kParamTable, kParamCount};
}

// Row of a parameter id, or nullptr when unknown.
constexpr const ParamDesc* find_param(std::uint16_t id) {
  for (const ParamDesc& p : kParamTable)
    if (p.id == id) return &p;
  return nullptr;
}

// Default of a defined parameter (every ParamId has a row in the table).
constexpr double param_default(ParamId id) {
  return find_param(static_cast<std::uint16_t>(id))->default_value;
}

// True when v is a legal value of p (finite, in range, whole when integer).
bool param_value_valid(const ParamDesc& p, double v);

}  // namespace petra
