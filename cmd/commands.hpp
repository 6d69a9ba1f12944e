// Telecommands as values, generated from cmd/command_defs.hpp: one argument
// struct per command (SelectRoiArgs, ...), the FunctionCode enum, the Command
// value the validator hands to the dispatcher, and the command table the ICD
// generator reads.
//
// Packet layout (big-endian), docs/icd.md "Telecommand packet":
//   [0,6)    CCSDS primary header: type 1, secondary header 1, APID kCommandApid, unsegmented
//   [6]      function code          [7] spare, 0
//   [8,12)   command counter (u32, strictly increasing per key)
//   [12,12+n) arguments of the function code
//   next 32  HMAC-SHA256 over bytes [0, 12+n) with the uplink key
//   last 2   CRC-16-CCITT over every byte before it
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <variant>

#include "algo/core/result.hpp"
#include "cmd/command_defs.hpp"

namespace petra::cmd {

inline constexpr std::uint16_t kCommandApid = 0x064;
inline constexpr std::size_t kTcHeaderBytes = 12;  // primary header + fc + spare + counter
inline constexpr std::size_t kHmacBytes = 32;
inline constexpr std::size_t kCrcBytes = 2;
inline constexpr std::size_t kTcOverheadBytes = kTcHeaderBytes + kHmacBytes + kCrcBytes;

enum class FunctionCode : std::uint8_t {
#define PETRA_CMD_ENUM(Name, NAME, code, modes, desc, FIELDS) NAME = (code),
  PETRA_COMMANDS(PETRA_CMD_ENUM)
#undef PETRA_CMD_ENUM
};

#define PETRA_CMD_STRUCT(Name, NAME, code, modes, desc, FIELDS) \
  PETRA_WIRE_STRUCT(Name##Args, FIELDS)
PETRA_COMMANDS(PETRA_CMD_STRUCT)
#undef PETRA_CMD_STRUCT

// The arguments of one command; monostate only in a default-constructed value.
using Args = std::variant<std::monostate
#define PETRA_CMD_ALT(Name, NAME, code, modes, desc, FIELDS) , Name##Args
                              PETRA_COMMANDS(PETRA_CMD_ALT)
#undef PETRA_CMD_ALT
                          >;

struct Command {
  FunctionCode code = FunctionCode::NOOP;
  std::uint32_t counter = 0;
  Args args;
};

struct CommandDesc {
  const char* name;
  std::uint8_t code;
  std::uint32_t allowed_modes;  // bit per Mode
  const char* description;
  std::span<const wire::FieldDesc> fields;
  std::size_t arg_bytes;
};

inline constexpr CommandDesc kCommandTable[] = {
#define PETRA_CMD_DESC(Name, NAME, code, modes, desc, FIELDS) \
  CommandDesc{#NAME, code, modes, desc, Name##Args::fields(), Name##Args::wire_bytes()},
    PETRA_COMMANDS(PETRA_CMD_DESC)
#undef PETRA_CMD_DESC
};

constexpr std::span<const CommandDesc> command_table() {
  return {kCommandTable, sizeof(kCommandTable) / sizeof(kCommandTable[0])};
}

constexpr std::size_t max_arg_bytes() {
  std::size_t n = 0;
  for (const CommandDesc& c : kCommandTable) n = c.arg_bytes > n ? c.arg_bytes : n;
  return n;
}
inline constexpr std::size_t kMinCommandBytes = kTcOverheadBytes;
inline constexpr std::size_t kMaxCommandBytes = kTcOverheadBytes + max_arg_bytes();

// Row of a function code / command name (exact, upper case), or nullptr.
const CommandDesc* find_command(std::uint8_t code);
const CommandDesc* find_command(std::string_view name);

// An Args value holding the default arguments of `code` (all zero).
Args default_args(FunctionCode code);

// Decodes the arguments of `code` from exactly desc.arg_bytes bytes.
Args decode_args(FunctionCode code, std::span<const std::uint8_t> bytes);
// Writes the arguments; returns the bytes written.
std::size_t encode_args(const Args& args, std::span<std::uint8_t> out);
// Index of the first argument outside its range, or -1.
int args_out_of_range(const Args& args);

}  // namespace petra::cmd
