// Binary PGM (P5, 8-bit) reading with a fixed read buffer: no heap, no stdio,
// so a camera backend can use it after init. The header is validated (magic,
// sizes, maxval <= 255, no truncation) and errors name the file and the field.
#pragma once

#include <array>
#include <cstdint>

#include "algo/core/image_view.hpp"
#include "algo/core/result.hpp"

namespace petra::hal {

struct PgmSize {
  int width = 0;
  int height = 0;
};

class PgmReader {
 public:
  // Reads only the header.
  Result<PgmSize> read_size(const char* path);
  // Reads the image into dst, whose size must equal the file's.
  Status read(const char* path, Gray8View dst);

 private:
  struct Header {
    PgmSize size;
    int maxval = 0;
    std::size_t data_offset = 0;
  };
  Result<Header> parse_header(const char* path, int fd);
  std::array<char, 4096> chunk_{};
};

}  // namespace petra::hal
