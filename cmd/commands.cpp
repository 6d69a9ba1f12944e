#include "cmd/commands.hpp"

#include <type_traits>

namespace petra::cmd {

const CommandDesc* find_command(std::uint8_t code) {
  for (const CommandDesc& c : kCommandTable)
    if (c.code == code) return &c;
  return nullptr;
}

const CommandDesc* find_command(std::string_view name) {
  for (const CommandDesc& c : kCommandTable)
    if (name == c.name) return &c;
  return nullptr;
}

Args default_args(FunctionCode code) {
  switch (code) {
#define PETRA_CMD_DEFAULT(Name, NAME, c, modes, desc, FIELDS) \
  case FunctionCode::NAME:                                    \
    return Name##Args{};
    PETRA_COMMANDS(PETRA_CMD_DEFAULT)
#undef PETRA_CMD_DEFAULT
  }
  return std::monostate{};
}

Args decode_args(FunctionCode code, std::span<const std::uint8_t> bytes) {
  Args args = default_args(code);
  wire::ByteReader r(bytes);
  std::visit(
      [&r](auto& a) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(a)>, std::monostate>) a.read(r);
      },
      args);
  return args;
}

std::size_t encode_args(const Args& args, std::span<std::uint8_t> out) {
  wire::ByteWriter w(out);
  std::visit(
      [&w](const auto& a) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(a)>, std::monostate>) a.write(w);
      },
      args);
  return w.overflow() ? 0 : w.size();
}

int args_out_of_range(const Args& args) {
  return std::visit(
      [](const auto& a) -> int {
        if constexpr (std::is_same_v<std::decay_t<decltype(a)>, std::monostate>) {
          return -1;
        } else {
          return a.out_of_range();
        }
      },
      args);
}

}  // namespace petra::cmd
