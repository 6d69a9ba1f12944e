// The vocabulary of the packet definitions: every field of every command and
// telemetry packet is one line  F(type, name, count, unit, min, max, "description")
// in an X-macro list (cmd/command_defs.hpp, tlm/tlm_defs.hpp). From that one line
// come the struct member, the big-endian encoder and decoder, the range check,
// and the FieldDesc row the ICD and XTCE generators read. Nothing is written twice.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>

#include "algo/wire/byte_io.hpp"

namespace petra::wire {

enum class FieldType : std::uint8_t { u8, u16, u32, i16, i32, f32, f64 };

using u8_t = std::uint8_t;
using u16_t = std::uint16_t;
using u32_t = std::uint32_t;
using i16_t = std::int16_t;
using i32_t = std::int32_t;
using f32_t = float;
using f64_t = double;

// A scalar, or a fixed array when count > 1.
template <class T, std::size_t N>
using Slot = std::conditional_t<N == 1, T, std::array<T, N>>;

struct FieldDesc {
  const char* name = nullptr;
  FieldType type = FieldType::u8;
  std::uint16_t count = 1;  // array length (1 = scalar)
  const char* unit = "";
  double min = 0;  // inclusive range, applied to every element
  double max = 0;
  const char* description = "";
};

constexpr std::size_t type_bytes(FieldType t) {
  switch (t) {
    case FieldType::u8:
      return 1;
    case FieldType::u16:
    case FieldType::i16:
      return 2;
    case FieldType::u32:
    case FieldType::i32:
    case FieldType::f32:
      return 4;
    case FieldType::f64:
      return 8;
  }
  return 0;
}

constexpr const char* type_name(FieldType t) {
  switch (t) {
    case FieldType::u8:
      return "u8";
    case FieldType::u16:
      return "u16";
    case FieldType::u32:
      return "u32";
    case FieldType::i16:
      return "i16";
    case FieldType::i32:
      return "i32";
    case FieldType::f32:
      return "f32";
    case FieldType::f64:
      return "f64";
  }
  return "?";
}

constexpr std::size_t fields_bytes(std::span<const FieldDesc> fields) {
  std::size_t n = 0;
  for (const FieldDesc& f : fields) n += type_bytes(f.type) * f.count;
  return n;
}

// Range check of one value (floating values must also be finite).
template <class T>
constexpr bool in_range(T v, double lo, double hi) {
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(v)) return false;
  }
  const double d = static_cast<double>(v);
  return d >= lo && d <= hi;
}
template <class T, std::size_t N>
constexpr bool in_range(const std::array<T, N>& a, double lo, double hi) {
  for (const T& v : a)
    if (!in_range(v, lo, hi)) return false;
  return true;
}

}  // namespace petra::wire

// ---- Expansion helpers applied to a field list F(type, name, count, unit, min, max, desc) ----

// `name` is the member being declared: it cannot take parentheses.
// NOLINTBEGIN(bugprone-macro-parentheses)
#define PETRA_WIRE_MEMBER(type, name, count, unit, lo, hi, desc) \
  ::petra::wire::Slot<::petra::wire::type##_t, count> name{};
// NOLINTEND(bugprone-macro-parentheses)
#define PETRA_WIRE_DESC(type, name, count, unit, lo, hi, desc) \
  ::petra::wire::FieldDesc{#name, ::petra::wire::FieldType::type, count, unit, lo, hi, desc},
#define PETRA_WIRE_WRITE(type, name, count, unit, lo, hi, desc) w.put(name);
#define PETRA_WIRE_READ(type, name, count, unit, lo, hi, desc) r.get(name);
#define PETRA_WIRE_RANGE(type, name, count, unit, lo, hi, desc) \
  if (!::petra::wire::in_range(name, lo, hi)) return index;     \
  ++index;
#define PETRA_WIRE_EACH(type, name, count, unit, lo, hi, desc) fn(#name, name);
#define PETRA_NO_FIELDS(F)

// Declares the struct `Name` with its members, codec, range check and field
// table from the list FIELDS. out_of_range() gives the index of the first bad
// field, or -1 when every field is within its range.
#define PETRA_WIRE_STRUCT(Name, FIELDS)                                                          \
  struct Name {                                                                                  \
    FIELDS(PETRA_WIRE_MEMBER)                                                                    \
    void write([[maybe_unused]] ::petra::wire::ByteWriter& w) const { FIELDS(PETRA_WIRE_WRITE) } \
    void read([[maybe_unused]] ::petra::wire::ByteReader& r) { FIELDS(PETRA_WIRE_READ) }         \
    int out_of_range() const {                                                                   \
      [[maybe_unused]] int index = 0;                                                            \
      FIELDS(PETRA_WIRE_RANGE)                                                                   \
      return -1;                                                                                 \
    }                                                                                            \
    /* Calls fn(name, member) for each field in wire order (ground tools). */                    \
    template <class Fn>                                                                          \
    void each([[maybe_unused]] Fn&& fn) const {                                                  \
      FIELDS(PETRA_WIRE_EACH)                                                                    \
    }                                                                                            \
    template <class Fn>                                                                          \
    void each([[maybe_unused]] Fn&& fn) {                                                        \
      FIELDS(PETRA_WIRE_EACH)                                                                    \
    }                                                                                            \
    static constexpr ::petra::wire::FieldDesc kFieldTable[] = {                                  \
        FIELDS(PETRA_WIRE_DESC)::petra::wire::FieldDesc{}};                                      \
    static constexpr std::span<const ::petra::wire::FieldDesc> fields() {                        \
      return {kFieldTable, sizeof(kFieldTable) / sizeof(kFieldTable[0]) - 1};                    \
    }                                                                                            \
    static constexpr std::size_t wire_bytes() { return ::petra::wire::fields_bytes(fields()); }  \
  };
