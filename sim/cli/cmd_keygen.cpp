// `petra keygen --out FILE`: a new 32-byte uplink key as 64 hex digits
// (libsodium's random generator), readable by its owner only.
#include <sodium.h>
#include <sys/stat.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "sim/cli/commands.hpp"

namespace petra::cli {

void add_keygen(CLI::App& app, Outcome& outcome) {
  auto* sub = app.add_subcommand("keygen", "Write a new uplink key (HMAC-SHA256, 32 bytes)");
  static std::string out;
  sub->add_option("--out", out, "key file to create")->required();
  sub->callback([&outcome] {
    if (sodium_init() < 0) {
      outcome.exit_code = fail("keygen", "libsodium failed to initialise");
      return;
    }
    unsigned char key[32];
    randombytes_buf(key, sizeof(key));
    char hex[65];
    sodium_bin2hex(hex, sizeof(hex), key, sizeof(key));
    sodium_memzero(key, sizeof(key));
    std::ofstream f(out, std::ios::trunc);
    f << hex << "\n";
    f.close();
    sodium_memzero(hex, sizeof(hex));
    if (!f || chmod(out.c_str(), 0600) != 0) {
      outcome.exit_code = fail("keygen", ("cannot write " + out).c_str());
      return;
    }
    std::printf("wrote uplink key %s (share it with petra-fsw's uplink.key_file)\n", out.c_str());
  });
}

}  // namespace petra::cli
