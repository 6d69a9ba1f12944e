// A heap-free JSON writer into a caller buffer. Numbers are written in the
// shortest form that reads back to the same double. Overflow is sticky: once
// the buffer is full every call is a no-op and finish() reports the error.
#pragma once

#include <cstddef>
#include <span>
#include <string_view>

#include "algo/core/result.hpp"

namespace petra::json {

class Writer {
 public:
  explicit Writer(std::span<char> out) : out_(out) {}

  Writer& begin_object();
  Writer& end_object();
  Writer& begin_array();
  Writer& end_array();
  Writer& key(std::string_view k);
  Writer& number(double v);
  Writer& integer(long long v);
  Writer& string(std::string_view s);
  Writer& boolean(bool b);
  Writer& raw(std::string_view s);  // formatting (newlines); no separator logic

  // Length written, or capacity_exceeded.
  Result<std::size_t> finish() const;
  std::string_view view() const { return {out_.data(), used_}; }

 private:
  void separator();
  void put(std::string_view s);

  std::span<char> out_;
  std::size_t used_ = 0;
  bool overflow_ = false;
  bool need_comma_ = false;
};

}  // namespace petra::json
