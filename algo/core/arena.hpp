// Bump arenas: every buffer of a pipeline run comes from one block fixed at
// init. Arena is the non-owning allocator over a caller block; StaticArena<N>
// owns a compile-time block. Exhaustion is an Error naming the request, and the
// high-water mark tells how much of the budget a run really used.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <new>
#include <span>
#include <type_traits>

#include "algo/core/result.hpp"

namespace petra {

class Arena {
 public:
  Arena() = default;
  explicit Arena(std::span<std::byte> block) : base_(block.data()), capacity_(block.size()) {}

  // Uninitialised-free: elements are value-initialised (trivial types only,
  // so a reset never needs destructors).
  template <class T>
  Result<std::span<T>> allocate(std::size_t count, const char* what = "buffer") {
    static_assert(std::is_trivially_destructible_v<T>, "arena holds trivially destructible types");
    auto r = reserve<T>(count, what);
    if (!r) return r.error();
    for (T& v : *r) new (&v) T{};
    return r;
  }

  // As allocate(), without the value-initialisation, for buffers their user
  // writes whole before reading them (the call says so): it spares a pass of
  // stores over memory about to be overwritten, which on a large scratch
  // buffer also evicts what the caches held.
  template <class T>
  Result<std::span<T>> allocate_uninitialised(std::size_t count, const char* what = "buffer") {
    static_assert(
        std::is_trivially_destructible_v<T> && std::is_trivially_default_constructible_v<T>,
        "no constructor to skip");
    auto r = reserve<T>(count, what);
#ifndef NDEBUG
    // Debug builds fill it with a pattern, so a user that reads before
    // writing fails its tests instead of reading the last run's values.
    if (r) std::memset(static_cast<void*>(r->data()), 0xA5, count * sizeof(T));
#endif
    return r;
  }

  // A mark to roll back to: scratch memory of one step is released after it.
  std::size_t mark() const {
    return used_;
  }
  void release_to(std::size_t mark) {
    PETRA_ASSERT(mark <= used_);
    used_ = mark;
  }
  void reset() {
    used_ = 0;
  }

  std::size_t used() const {
    return used_;
  }
  std::size_t capacity() const {
    return capacity_;
  }
  std::size_t remaining() const {
    return capacity_ - used_;
  }
  std::size_t high_water() const {
    return high_water_;
  }

 private:
  template <class T>
  Result<std::span<T>> reserve(std::size_t count, const char* what) {
    // Aligned as an address, not as an offset: a caller's block need only be
    // byte-aligned, and over-aligned types (vector rows) get what they ask.
    const std::size_t align = alignof(T);
    const std::uintptr_t at = reinterpret_cast<std::uintptr_t>(base_) + used_;
    const std::size_t start = used_ + ((align - at % align) % align);
    if (count > (SIZE_MAX - start) / sizeof(T) || start + count * sizeof(T) > capacity_) {
      return Error::make(Errc::capacity_exceeded, "arena: %s needs %zu bytes, %zu of %zu free",
                         what, count * sizeof(T), capacity_ - used_, capacity_);
    }
    T* p = reinterpret_cast<T*>(base_ + start);  // NOLINT: storage reuse is the point
    used_ = start + count * sizeof(T);
    if (used_ > high_water_) high_water_ = used_;
    return std::span<T>(p, count);
  }

  std::byte* base_ = nullptr;
  std::size_t capacity_ = 0;
  std::size_t used_ = 0;
  std::size_t high_water_ = 0;
};

// Budgets count this much padding per allocation: enough to start any
// buffer of the flight code on a 64-byte cache line (the matchers' rows).
inline constexpr std::size_t kArenaSlackPerAllocation = 64;

// The most an allocate<T>(count) can take from an arena: the elements and
// the padding to T's alignment. Budgets are sums of these.
template <class T>
constexpr std::size_t arena_bytes_for(std::size_t count) {
  return count * sizeof(T) + alignof(T);
}

// Scoped scratch: releases everything allocated after construction.
class ArenaScope {
 public:
  explicit ArenaScope(Arena& arena) : arena_(arena), mark_(arena.mark()) {}
  ~ArenaScope() { arena_.release_to(mark_); }
  ArenaScope(const ArenaScope&) = delete;
  ArenaScope& operator=(const ArenaScope&) = delete;

 private:
  Arena& arena_;
  std::size_t mark_;
};

template <std::size_t N>
class StaticArena {
 public:
  StaticArena() : arena_(std::span<std::byte>(block_, N)) {}
  StaticArena(const StaticArena&) = delete;
  StaticArena& operator=(const StaticArena&) = delete;
  Arena& arena() { return arena_; }
  static constexpr std::size_t capacity() { return N; }

 private:
  alignas(std::max_align_t) std::byte block_[N];
  Arena arena_;
};

}  // namespace petra
