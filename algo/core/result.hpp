// Result<T>: a value or an Error, in the spirit of std::expected (C++23), for
// C++20 flight code. Accessing the wrong alternative is a programming error and
// aborts through PETRA_ASSERT; it never throws.
#pragma once

#include <new>
#include <type_traits>
#include <utility>

#include "algo/core/assert.hpp"
#include "algo/core/error.hpp"

namespace petra {

template <class T>
class [[nodiscard]] Result {
 public:
  Result(const T& value) : has_value_(true) { new (&storage_.value) T(value); }           // NOLINT
  Result(T&& value) : has_value_(true) { new (&storage_.value) T(std::move(value)); }     // NOLINT
  Result(const Error& error) : has_value_(false) { new (&storage_.error) Error(error); }  // NOLINT

  Result(const Result& other) : has_value_(other.has_value_) {
    if (has_value_)
      new (&storage_.value) T(other.storage_.value);
    else
      new (&storage_.error) Error(other.storage_.error);
  }
  Result(Result&& other) noexcept : has_value_(other.has_value_) {
    if (has_value_)
      new (&storage_.value) T(std::move(other.storage_.value));
    else
      new (&storage_.error) Error(other.storage_.error);
  }
  Result& operator=(Result other) noexcept {
    this->~Result();
    new (this) Result(std::move(other));
    return *this;
  }
  ~Result() {
    if (has_value_) storage_.value.~T();
  }

  bool ok() const noexcept { return has_value_; }
  explicit operator bool() const noexcept { return has_value_; }

  T& value() & {
    PETRA_ASSERT(has_value_);
    return storage_.value;
  }
  const T& value() const& {
    PETRA_ASSERT(has_value_);
    return storage_.value;
  }
  T&& value() && {
    PETRA_ASSERT(has_value_);
    return std::move(storage_.value);
  }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

  const Error& error() const {
    PETRA_ASSERT(!has_value_);
    return storage_.error;
  }
  Errc code() const noexcept { return has_value_ ? Errc::ok : storage_.error.code; }

 private:
  union Storage {
    Storage() {}
    ~Storage() {}
    T value;
    Error error;
  } storage_;
  bool has_value_;
};

// Status: success or an Error.
template <>
class [[nodiscard]] Result<void> {
 public:
  Result() = default;
  Result(const Error& error) : error_(error) {}  // NOLINT
  bool ok() const noexcept { return error_.code == Errc::ok; }
  explicit operator bool() const noexcept { return ok(); }
  const Error& error() const {
    PETRA_ASSERT(!ok());
    return error_;
  }
  Errc code() const noexcept { return error_.code; }

 private:
  Error error_{};
};

using Status = Result<void>;

inline Status ok_status() {
  return Status{};
}

}  // namespace petra

// Propagate an error from an expression yielding a Result/Status.
#define PETRA_TRY(expr)                                            \
  do {                                                             \
    auto petra_try_result_ = (expr);                               \
    if (!petra_try_result_.ok()) return petra_try_result_.error(); \
  } while (false)
