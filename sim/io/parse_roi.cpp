#include "sim/io/parse_roi.hpp"

#include <cerrno>
#include <cstdlib>

namespace petra::io {

Result<Rect> parse_roi(const std::string& text) {
  int v[4] = {};
  const char* p = text.c_str();
  for (int i = 0; i < 4; ++i) {
    char* end = nullptr;
    errno = 0;
    const long x = std::strtol(p, &end, 10);
    if (end == p || errno != 0 || x < -1000000 || x > 1000000)
      return Error::make(Errc::parse_error, "--roi \"%s\": expected x,y,w,h (four integers)",
                         text.c_str());
    v[i] = static_cast<int>(x);
    p = end;
    if (i < 3) {
      if (*p != ',')
        return Error::make(Errc::parse_error, "--roi \"%s\": expected x,y,w,h", text.c_str());
      ++p;
    }
  }
  if (*p != '\0')
    return Error::make(Errc::parse_error, "--roi \"%s\": extra text after x,y,w,h", text.c_str());
  if (v[2] <= 0 || v[3] <= 0)
    return Error::make(Errc::invalid_argument, "--roi \"%s\": width and height must be > 0",
                       text.c_str());
  return Rect{v[0], v[1], v[2], v[3]};
}

}  // namespace petra::io
