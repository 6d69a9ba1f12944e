// Big-endian (network order, as CCSDS) readers and writers over caller
// buffers. Overrun is sticky and checked once at the end, so packet codecs stay
// straight-line code and can never write or read past the buffer.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>

namespace petra::wire {

class ByteWriter {
 public:
  explicit ByteWriter(std::span<std::uint8_t> out) : out_(out) {}

  void u8(std::uint8_t v) { put_be(v, 1); }
  void u16(std::uint16_t v) { put_be(v, 2); }
  void u32(std::uint32_t v) { put_be(v, 4); }
  void u64(std::uint64_t v) { put_be(v, 8); }
  void bytes(std::span<const std::uint8_t> b) {
    if (!room(b.size())) return;
    for (std::size_t i = 0; i < b.size(); ++i) out_[used_ + i] = b[i];
    used_ += b.size();
  }

  void put(std::uint8_t v) { u8(v); }
  void put(std::uint16_t v) { u16(v); }
  void put(std::uint32_t v) { u32(v); }
  void put(std::int16_t v) { u16(static_cast<std::uint16_t>(v)); }
  void put(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void put(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
  void put(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
  template <class T, std::size_t N>
  void put(const std::array<T, N>& a) {
    for (const T& v : a) put(v);
  }

  std::size_t size() const { return used_; }
  bool overflow() const { return overflow_; }

 private:
  bool room(std::size_t n) {
    if (overflow_ || n > out_.size() - used_) {
      overflow_ = true;
      return false;
    }
    return true;
  }
  void put_be(std::uint64_t v, std::size_t n) {
    if (!room(n)) return;
    for (std::size_t i = 0; i < n; ++i)
      out_[used_ + i] = static_cast<std::uint8_t>(v >> (8 * (n - 1 - i)));
    used_ += n;
  }

  std::span<std::uint8_t> out_;
  std::size_t used_ = 0;
  bool overflow_ = false;
};

class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> in) : in_(in) {}

  std::uint8_t u8() { return static_cast<std::uint8_t>(get_be(1)); }
  std::uint16_t u16() { return static_cast<std::uint16_t>(get_be(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(get_be(4)); }
  std::uint64_t u64() { return get_be(8); }

  void get(std::uint8_t& v) { v = u8(); }
  void get(std::uint16_t& v) { v = u16(); }
  void get(std::uint32_t& v) { v = u32(); }
  void get(std::int16_t& v) { v = static_cast<std::int16_t>(u16()); }
  void get(std::int32_t& v) { v = static_cast<std::int32_t>(u32()); }
  void get(float& v) { v = std::bit_cast<float>(u32()); }
  void get(double& v) { v = std::bit_cast<double>(u64()); }
  template <class T, std::size_t N>
  void get(std::array<T, N>& a) {
    for (T& v : a) get(v);
  }

  std::size_t position() const { return pos_; }
  std::size_t remaining() const { return in_.size() - pos_; }
  bool underflow() const { return underflow_; }

 private:
  std::uint64_t get_be(std::size_t n) {
    if (underflow_ || n > in_.size() - pos_) {
      underflow_ = true;
      return 0;
    }
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < n; ++i) v = (v << 8) | in_[pos_ + i];
    pos_ += n;
    return v;
  }

  std::span<const std::uint8_t> in_;
  std::size_t pos_ = 0;
  bool underflow_ = false;
};

}  // namespace petra::wire
