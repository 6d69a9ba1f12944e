#include "algo/core/assert.hpp"

#include <cstdio>
#include <cstdlib>

namespace petra {

// The only place algo/ touches stderr: an invariant is broken and we stop.
void assert_fail(const char* expr, const char* file, int line) noexcept {
  (void)std::fprintf(stderr, "PETRA_ASSERT failed: %s at %s:%d\n", expr, file, line);
  std::abort();
}

}  // namespace petra
