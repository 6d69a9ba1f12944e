// Command authentication: HMAC-SHA256 (libsodium crypto_auth_hmacsha256) with
// a 32-byte uplink key. The key file holds the key as 64 hexadecimal digits
// (whitespace around them is ignored); `petra keygen` writes one.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "algo/core/result.hpp"

namespace petra::cmd {

inline constexpr std::size_t kKeyBytes = 32;
inline constexpr std::size_t kMacBytes = 32;

struct AuthKey {
  std::array<std::uint8_t, kKeyBytes> bytes{};
};

using Mac = std::array<std::uint8_t, kMacBytes>;

// Initialises libsodium once (call at init; safe to call again).
Status auth_init();

// Reads a key file (no heap: fixed buffer, POSIX read). Errors name the file and problem.
Result<AuthKey> load_key_file(const char* path);
// Parses 64 hex digits surrounded by optional whitespace.
Result<AuthKey> parse_key_hex(std::span<const char> text);

Mac compute_mac(const AuthKey& key, std::span<const std::uint8_t> message);
// A key's public name: the first 8 bytes of HMAC(key, "petra uplink key id").
// The counter file carries it, so a new key is recognised (and gets a new
// counter window) without revealing anything about the key.
using KeyId = std::array<std::uint8_t, 8>;
KeyId key_id(const AuthKey& key);

// Constant-time comparison.
bool verify_mac(const AuthKey& key, std::span<const std::uint8_t> message,
                std::span<const std::uint8_t> mac);

}  // namespace petra::cmd
