#include "algo/core/error.hpp"

#include <cstdarg>

namespace petra {

const char* errc_name(Errc code) noexcept {
  switch (code) {
    case Errc::ok:
      return "ok";
    case Errc::invalid_argument:
      return "invalid_argument";
    case Errc::out_of_range:
      return "out_of_range";
    case Errc::capacity_exceeded:
      return "capacity_exceeded";
    case Errc::parse_error:
      return "parse_error";
    case Errc::missing_field:
      return "missing_field";
    case Errc::wrong_type:
      return "wrong_type";
    case Errc::not_orthonormal:
      return "not_orthonormal";
    case Errc::non_positive:
      return "non_positive";
    case Errc::no_solution:
      return "no_solution";
    case Errc::degenerate:
      return "degenerate";
    case Errc::io_error:
      return "io_error";
    case Errc::not_ready:
      return "not_ready";
    case Errc::timeout:
      return "timeout";
    case Errc::cancelled:
      return "cancelled";
  }
  return "unknown";
}

Error Error::make(Errc code, const char* fmt, ...) noexcept {
  Error e;
  e.code = code;
  va_list args;
  va_start(args, fmt);
  // A longer message is cut to the capacity (still terminated): acceptable
  // for a diagnostic. The analyser's uninitialised va_list is a false
  // positive (va_start is on the line above).
  // NOLINTNEXTLINE(clang-analyzer-valist.Uninitialized)
  (void)std::vsnprintf(e.message, kMessageCapacity, fmt, args);
  va_end(args);
  return e;
}

}  // namespace petra
