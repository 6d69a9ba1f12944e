// Errors as values for all flight code: a code plus a short fixed-size message
// naming the field or limit at fault. No heap, no exceptions.
#pragma once

#include <cstdint>
#include <cstdio>

namespace petra {

enum class Errc : std::uint16_t {
  ok = 0,
  invalid_argument,   // a value outside its documented domain
  out_of_range,       // an index, ROI or range outside the image or table
  capacity_exceeded,  // a budget or fixed capacity would be exceeded
  parse_error,        // malformed text or binary input
  missing_field,      // a required field is absent
  wrong_type,         // a field has the wrong type
  not_orthonormal,    // a rotation matrix is not a rotation
  non_positive,       // a length or scale that must be > 0 is not
  no_solution,        // a numeric problem has no solution in the valid domain
  degenerate,         // geometry or data too degenerate to continue
  io_error,           // the OS refused (used by hal/ and tools, never algo/)
  not_ready,          // called in the wrong state
  timeout,            // a bounded wait ran out
  cancelled,          // the caller asked a long computation to stop
};

const char* errc_name(Errc code) noexcept;

struct Error {
  static constexpr std::size_t kMessageCapacity = 120;
  Errc code = Errc::ok;
  char message[kMessageCapacity] = {};

  // printf-style message; truncated (never overflows) when too long.
  [[gnu::format(printf, 2, 3)]] static Error make(Errc code, const char* fmt, ...) noexcept;
};

}  // namespace petra
