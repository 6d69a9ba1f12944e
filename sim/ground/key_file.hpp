// A new uplink key on disk, as `petra keygen` and the demo write it: the key
// file (64 hex digits, mode 0600, an existing one kept unless `overwrite`),
// the flight counter beside it (KEY.fsw-counter at 0, bound to this key, so
// petra-fsw starts on it) and the ground's counter (KEY.counter) removed so
// `petra cmd` starts again at 1 under the new key.
#pragma once

#include <string>

#include "algo/core/result.hpp"
#include "cmd/auth.hpp"

namespace petra::ground {

Status write_new_key(const std::string& path, const cmd::AuthKey& key, bool overwrite);

}  // namespace petra::ground
