// PETRA_ASSERT guards programming errors (broken invariants), not bad input:
// bad input is always reported as an Error value. It is active in every build.
#pragma once

namespace petra {
[[noreturn]] void assert_fail(const char* expr, const char* file, int line) noexcept;
}

#define PETRA_ASSERT(cond) \
  ((cond) ? static_cast<void>(0) : ::petra::assert_fail(#cond, __FILE__, __LINE__))
