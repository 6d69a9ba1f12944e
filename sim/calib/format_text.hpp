// printf into a std::string, for the calibration's notes and reports.
#pragma once

#include <string>

namespace petra::calib {

[[gnu::format(printf, 1, 2)]] std::string format_text(const char* fmt, ...);

}  // namespace petra::calib
