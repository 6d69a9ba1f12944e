#include "cmd/auth.hpp"

#include <fcntl.h>
#include <sodium.h>
#include <unistd.h>

namespace petra::cmd {

static_assert(crypto_auth_hmacsha256_KEYBYTES == kKeyBytes);
static_assert(crypto_auth_hmacsha256_BYTES == kMacBytes);

Status auth_init() {
  if (sodium_init() < 0) return Error::make(Errc::io_error, "libsodium: sodium_init failed");
  return {};
}

namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

bool is_space(char c) {
  return c == ' ' || c == '\n' || c == '\r' || c == '\t';
}

}  // namespace

Result<AuthKey> parse_key_hex(std::span<const char> text) {
  std::size_t begin = 0;
  std::size_t end = text.size();
  while (begin < end && is_space(text[begin])) ++begin;
  while (end > begin && is_space(text[end - 1])) --end;
  if (end - begin != 2 * kKeyBytes)
    return Error::make(Errc::parse_error, "key: expected %zu hex digits, found %zu characters",
                       2 * kKeyBytes, end - begin);
  AuthKey key;
  for (std::size_t i = 0; i < kKeyBytes; ++i) {
    const int hi = hex_value(text[begin + 2 * i]);
    const int lo = hex_value(text[begin + 2 * i + 1]);
    if (hi < 0 || lo < 0)
      return Error::make(Errc::parse_error, "key: character %zu is not a hex digit",
                         begin + 2 * i + (hi < 0 ? 0 : 1));
    key.bytes[i] = static_cast<std::uint8_t>(hi * 16 + lo);
  }
  return key;
}

Result<AuthKey> load_key_file(const char* path) {
  const int fd = ::open(path, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return Error::make(Errc::io_error, "key file %s: cannot open", path);
  char buf[256];
  std::size_t used = 0;
  for (;;) {  // bounded: stops when the buffer is full
    const ssize_t n = ::read(fd, buf + used, sizeof(buf) - used);
    if (n <= 0) break;
    used += static_cast<std::size_t>(n);
    if (used == sizeof(buf)) break;
  }
  ::close(fd);
  if (used == sizeof(buf)) return Error::make(Errc::parse_error, "key file %s: too long", path);
  auto key = parse_key_hex(std::span<const char>(buf, used));
  sodium_memzero(buf, sizeof(buf));
  if (!key) return Error::make(Errc::parse_error, "key file %s: %s", path, key.error().message);
  return key;
}

Mac compute_mac(const AuthKey& key, std::span<const std::uint8_t> message) {
  Mac mac{};
  crypto_auth_hmacsha256(mac.data(), message.data(), message.size(), key.bytes.data());
  return mac;
}

KeyId key_id(const AuthKey& key) {
  static constexpr char kLabel[] = "petra uplink key id";
  const Mac mac = compute_mac(
      key, std::span(reinterpret_cast<const std::uint8_t*>(kLabel), sizeof(kLabel) - 1));
  KeyId id{};
  for (std::size_t i = 0; i < id.size(); ++i) id[i] = mac[i];
  return id;
}

bool verify_mac(const AuthKey& key, std::span<const std::uint8_t> message,
                std::span<const std::uint8_t> mac) {
  if (mac.size() != kMacBytes) return false;
  return crypto_auth_hmacsha256_verify(mac.data(), message.data(), message.size(),
                                       key.bytes.data()) == 0;
}

}  // namespace petra::cmd
