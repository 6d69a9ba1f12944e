#include "tests/support/heap_counter.hpp"

#include <atomic>
#include <cstdlib>
#include <new>

#include <Eigen/Core>

namespace {
std::atomic<std::size_t> g_allocations{0};
}

#if defined(__SANITIZE_ADDRESS__)
// ASan owns malloc: its allocator calls this hook on every allocation (malloc,
// calloc, realloc, aligned_alloc and the operator new below), so every one is
// counted once, as without the sanitizer.
// (The sanitizer runtime's interface; g++ ships no header for it.)
extern "C" int __sanitizer_install_malloc_and_free_hooks(
    void (*malloc_hook)(const volatile void*, std::size_t), void (*free_hook)(const volatile void*));
#define PETRA_COUNT_MALLOC 0
namespace {
void count_allocation(const volatile void*, std::size_t) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
}
void ignore_free(const volatile void*) {}
// Non-zero when installed (the runtime takes both hooks or none).
const int g_hook_installed =
    __sanitizer_install_malloc_and_free_hooks(count_allocation, ignore_free);
}  // namespace
#else
#define PETRA_COUNT_MALLOC 1
// glibc's own entry points, so the replacements below can forward to them.
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void __libc_free(void*);
void* malloc(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t m) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(n, m);
}
void* realloc(void* p, std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(p, n);
}
void free(void* p) {
  __libc_free(p);
}
}
#endif

namespace {
void* counted_new(std::size_t n) {  // counted by malloc (or ASan's hook)
  void* p = std::malloc(n == 0 ? 1 : n);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
void* counted_new_aligned(std::size_t n, std::align_val_t al) {
#if PETRA_COUNT_MALLOC  // aligned_alloc is not replaced; ASan's hook counts it
  g_allocations.fetch_add(1, std::memory_order_relaxed);
#endif
  const std::size_t a = static_cast<std::size_t>(al);
  void* p = std::aligned_alloc(a, (n + a - 1) / a * a);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
}  // namespace

void* operator new(std::size_t n) {
  return counted_new(n);
}
void* operator new[](std::size_t n) {
  return counted_new(n);
}
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return counted_new(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return counted_new(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new(std::size_t n, std::align_val_t a) {
  return counted_new_aligned(n, a);
}
void* operator new[](std::size_t n, std::align_val_t a) {
  return counted_new_aligned(n, a);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}

namespace petra::test {

std::size_t total_allocations() {
  return g_allocations.load(std::memory_order_relaxed);
}
bool counts_malloc() {
#if defined(__SANITIZE_ADDRESS__)
  return g_hook_installed != 0;
#else
  return true;
#endif
}

HeapScope::HeapScope()
    : start_(total_allocations()), eigen_was_allowed_(Eigen::internal::is_malloc_allowed()) {
  Eigen::internal::set_is_malloc_allowed(false);
}

HeapScope::~HeapScope() {
  Eigen::internal::set_is_malloc_allowed(eigen_was_allowed_);
}

std::size_t HeapScope::allocations() const {
  return total_allocations() - start_;
}

}  // namespace petra::test
