// ParamTable: current values of the parameters of cmd/param_defs.hpp. Values
// are validated on every set (range, whole numbers); defaults come from the
// definitions, then from the defaults file at boot ({"NAME": value, ...}).
#pragma once

#include <array>
#include <cstddef>

#include "algo/core/result.hpp"
#include "cmd/param_defs.hpp"

namespace petra::fsw {

class ParamTable {
 public:
  ParamTable();
  double get(ParamId id) const;
  int get_int(ParamId id) const { return static_cast<int>(get(id)); }
  // Value by wire id; false when unknown.
  bool get(std::uint16_t id, double& value) const;
  Status set(std::uint16_t id, double value);
  // Applies a defaults file's JSON text; returns how many parameters it set.
  Result<int> load_defaults(const char* text, std::size_t size);

 private:
  std::array<double, kParamCount> values_{};
};

}  // namespace petra::fsw
