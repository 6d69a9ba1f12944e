#include "cmd/param_defs.hpp"

#include <cmath>

namespace petra {

bool param_value_valid(const ParamDesc& p, double v) {
  if (!std::isfinite(v) || v < p.min || v > p.max) return false;
  return !p.integer || std::floor(v) == v;
}

}  // namespace petra
