#include "sim/io/parse_point.hpp"

#include <cerrno>
#include <climits>
#include <cstdlib>

namespace petra::io {

Result<PixelPoint> parse_point(const std::string& text) {
  long values[2] = {0, 0};
  const char* p = text.c_str();
  for (int k = 0; k < 2; ++k) {
    char* end = nullptr;
    errno = 0;
    values[k] = std::strtol(p, &end, 10);
    if (end == p || errno != 0 || values[k] < INT_MIN || values[k] > INT_MAX)
      return Error::make(Errc::parse_error, "point \"%.40s\": expected u,v (two integers)",
                         text.c_str());
    p = end;
    if (k == 0) {
      if (*p != ',')
        return Error::make(Errc::parse_error, "point \"%.40s\": expected u,v (two integers)",
                           text.c_str());
      ++p;
    }
  }
  if (*p != '\0')
    return Error::make(Errc::parse_error, "point \"%.40s\": unexpected text after u,v",
                       text.c_str());
  return PixelPoint{static_cast<int>(values[0]), static_cast<int>(values[1])};
}

}  // namespace petra::io
