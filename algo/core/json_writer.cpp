#include "algo/core/json_writer.hpp"

#include <charconv>
#include <cmath>

namespace petra::json {

void Writer::put(std::string_view s) {
  if (overflow_) return;
  if (s.size() > out_.size() - used_) {
    overflow_ = true;
    return;
  }
  for (char c : s) out_[used_++] = c;
}

void Writer::separator() {
  if (need_comma_) put(",");
}

Writer& Writer::begin_object() {
  separator();
  put("{");
  need_comma_ = false;
  return *this;
}
Writer& Writer::end_object() {
  put("}");
  need_comma_ = true;
  return *this;
}
Writer& Writer::begin_array() {
  separator();
  put("[");
  need_comma_ = false;
  return *this;
}
Writer& Writer::end_array() {
  put("]");
  need_comma_ = true;
  return *this;
}

Writer& Writer::key(std::string_view k) {
  string(k);
  put(":");
  need_comma_ = false;
  return *this;
}

Writer& Writer::number(double v) {
  separator();
  if (!std::isfinite(v)) {
    put("null");  // JSON has no inf/nan; readers reject it as a wrong type
  } else {
    char buf[32];
    auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v);
    if (ec != std::errc{})
      overflow_ = true;
    else
      put({buf, static_cast<std::size_t>(ptr - buf)});
  }
  need_comma_ = true;
  return *this;
}

Writer& Writer::integer(long long v) {
  separator();
  char buf[24];
  auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v);
  if (ec != std::errc{})
    overflow_ = true;
  else
    put({buf, static_cast<std::size_t>(ptr - buf)});
  need_comma_ = true;
  return *this;
}

Writer& Writer::string(std::string_view s) {
  separator();
  put("\"");
  for (char c : s) {
    if (c == '"')
      put("\\\"");
    else if (c == '\\')
      put("\\\\");
    else if (c == '\n')
      put("\\n");
    else if (static_cast<unsigned char>(c) < 0x20)
      put("?");
    else
      put({&c, 1});
  }
  put("\"");
  need_comma_ = true;
  return *this;
}

Writer& Writer::boolean(bool b) {
  separator();
  put(b ? "true" : "false");
  need_comma_ = true;
  return *this;
}

Writer& Writer::raw(std::string_view s) {
  put(s);
  return *this;
}

Result<std::size_t> Writer::finish() const {
  if (overflow_)
    return Error::make(Errc::capacity_exceeded, "json writer: output exceeds %zu bytes",
                       out_.size());
  return used_;
}

}  // namespace petra::json
