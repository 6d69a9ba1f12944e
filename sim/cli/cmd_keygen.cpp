// `petra keygen --out FILE [--force]`: a new 32-byte uplink key as 64 hex
// digits (libsodium's random generator), readable by its owner only, with its
// flight counter beside it (FILE.fsw-counter). An existing key is kept unless
// --force: replacing it is re-keying (docs/ops.md "Command counter").
#include <sodium.h>

#include <cstdio>
#include <string>

#include "sim/cli/commands.hpp"
#include "sim/ground/key_file.hpp"

namespace petra::cli {

void add_keygen(CLI::App& app, Outcome& outcome) {
  auto* sub = app.add_subcommand("keygen", "Write a new uplink key (HMAC-SHA256, 32 bytes)");
  static std::string out;
  static bool force = false;
  sub->add_option("--out", out, "key file to create")->required();
  sub->add_flag("--force", force, "replace an existing key (re-keying: a new counter window)");
  sub->callback([&outcome] {
    if (sodium_init() < 0) {
      outcome.exit_code = fail("keygen", "libsodium failed to initialise");
      return;
    }
    cmd::AuthKey key;
    randombytes_buf(key.bytes.data(), key.bytes.size());
    const Status s = ground::write_new_key(out, key, force);
    sodium_memzero(key.bytes.data(), key.bytes.size());
    if (!s) {
      outcome.exit_code = fail("keygen", s.error().message);
      return;
    }
    std::printf(
        "wrote uplink key %s and its flight counter %s.fsw-counter (mode 0600; install both "
        "where petra-fsw's uplink.key_file points)\n",
        out.c_str(), out.c_str());
  });
}

}  // namespace petra::cli
