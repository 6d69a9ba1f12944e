// Reading whole small files (configuration, keys, parameters, calibration)
// into caller buffers with POSIX calls: no heap, no stdio.
#pragma once

#include <cstddef>
#include <span>

#include "algo/core/result.hpp"

namespace petra::hal {

// Reads the file into buf; returns its size. A file larger than buf is an error.
Result<std::size_t> read_small_file(const char* path, std::span<char> buf);

// Replaces the file's content (write to path.tmp, then rename: never half-written).
// No fsync: it costs milliseconds per call in the loop; the rename keeps the
// file whole across a process crash (a power loss may lose the last update).
Status write_small_file(const char* path, std::span<const char> data);

// dir/name into out (NUL-terminated); name as is when absolute or dir empty.
Status join_path(const char* dir, const char* name, std::span<char> out);

}  // namespace petra::hal
