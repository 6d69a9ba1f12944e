// The text of an errno value for an error message, without allocating:
// strerrordesc_np returns a static string (strerror may build one for an
// unknown code, and the hal reports errors after init).
#pragma once

#include <cstring>

namespace petra::hal {

inline const char* errno_text(int err) {
  const char* s = strerrordesc_np(err);
  return s != nullptr ? s : "unknown error";
}

}  // namespace petra::hal
