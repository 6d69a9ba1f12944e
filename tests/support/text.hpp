// Text helpers of the tests: a whole file as a string (the tests' outputs:
// JSON, logs; empty when the file cannot be read, which the test's own checks
// then report) and a number in three significant digits for messages.
#pragma once

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace petra::test {

inline std::string read_all(const std::filesystem::path& p) {
  std::stringstream s;
  s << std::ifstream(p).rdbuf();
  return s.str();
}

inline std::string sci(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace petra::test
