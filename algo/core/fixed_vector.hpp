// FixedVector<T, N>: a vector with inline storage for at most N elements.
// push_back on a full vector fails with a value, never reallocates.
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include "algo/core/assert.hpp"

namespace petra {

template <class T, std::size_t N>
class FixedVector {
 public:
  static constexpr std::size_t kCapacity = N;

  constexpr std::size_t size() const { return size_; }
  static constexpr std::size_t capacity() { return N; }
  constexpr bool empty() const { return size_ == 0; }
  constexpr bool full() const { return size_ == N; }

  // Returns false (and changes nothing) when full.
  [[nodiscard]] constexpr bool push_back(const T& v) {
    if (size_ == N) return false;
    items_[size_++] = v;
    return true;
  }
  constexpr void pop_back() {
    PETRA_ASSERT(size_ > 0);
    --size_;
  }
  constexpr void clear() { size_ = 0; }
  // Shrinks, or grows with value-initialised elements up to capacity.
  [[nodiscard]] constexpr bool resize(std::size_t n) {
    if (n > N) return false;
    for (std::size_t i = size_; i < n; ++i) items_[i] = T{};
    size_ = n;
    return true;
  }

  constexpr T& operator[](std::size_t i) {
    PETRA_ASSERT(i < size_);
    return items_[i];
  }
  constexpr const T& operator[](std::size_t i) const {
    PETRA_ASSERT(i < size_);
    return items_[i];
  }
  constexpr T& back() {
    PETRA_ASSERT(size_ > 0);
    return items_[size_ - 1];
  }
  constexpr const T& back() const {
    PETRA_ASSERT(size_ > 0);
    return items_[size_ - 1];
  }

  constexpr T* begin() { return items_.data(); }
  constexpr T* end() { return items_.data() + size_; }
  constexpr const T* begin() const { return items_.data(); }
  constexpr const T* end() const { return items_.data() + size_; }
  constexpr T* data() { return items_.data(); }
  constexpr const T* data() const { return items_.data(); }

  std::span<T> span() { return {items_.data(), size_}; }
  std::span<const T> span() const { return {items_.data(), size_}; }

 private:
  std::array<T, N> items_{};
  std::size_t size_ = 0;
};

}  // namespace petra
