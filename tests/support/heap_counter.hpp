// Counts heap allocations in a test binary. Linking heap_counter.cpp replaces
// the global operator new/delete family and malloc/calloc/realloc (under ASan,
// which owns malloc, its allocator hook counts instead), so every allocation
// by any thread is counted. HeapScope measures a block:
//
//   petra::test::HeapScope scope;
//   run_steady_state();
//   EXPECT_EQ(scope.allocations(), 0u);
//
// It also forbids Eigen heap use inside the scope (EIGEN_RUNTIME_NO_MALLOC),
// which turns a hidden Eigen allocation into an assertion (Debug builds; with
// NDEBUG the count still catches it).
#pragma once

#include <cstddef>

namespace petra::test {

std::size_t total_allocations();
bool counts_malloc();  // false only if ASan refused the allocation hook

class HeapScope {
 public:
  HeapScope();
  ~HeapScope();
  HeapScope(const HeapScope&) = delete;
  HeapScope& operator=(const HeapScope&) = delete;
  std::size_t allocations() const;

 private:
  std::size_t start_;
  bool eigen_was_allowed_;
};

}  // namespace petra::test
