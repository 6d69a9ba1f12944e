#include "algo/core/arena.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

TEST(Arena, AllocatesAlignedAndTracksHighWater) {
  StaticArena<1024> storage;
  Arena& a = storage.arena();
  auto bytes = a.allocate<std::uint8_t>(3);
  ASSERT_TRUE(bytes.ok());
  auto doubles = a.allocate<double>(4);
  ASSERT_TRUE(doubles.ok());
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(doubles->data()) % alignof(double), 0u);
  EXPECT_EQ(a.used(), 8u + 32u);
  EXPECT_EQ(a.high_water(), 40u);
  a.reset();
  EXPECT_EQ(a.used(), 0u);
  EXPECT_EQ(a.high_water(), 40u);
}

// A vector row type asks for more than max_align_t; the block the caller
// gives may start anywhere (here 8 bytes into a 64-byte line).
struct alignas(64) WideRow {
  std::uint16_t lanes[32];
};

TEST(Arena, OverAlignedTypesAreAlignedAsAddressesInAnyBlock) {
  alignas(64) std::byte storage[1024];
  for (std::size_t skew : {0u, 1u, 8u, 16u, 40u}) {
    Arena a(std::span<std::byte>(storage + skew, sizeof(storage) - skew));
    ASSERT_TRUE(a.allocate<std::uint8_t>(3).ok());
    auto row = a.allocate<WideRow>(2);
    ASSERT_TRUE(row.ok()) << "skew " << skew;
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(row->data()) % 64u, 0u) << "skew " << skew;
    EXPECT_LE(a.used(), sizeof(storage) - skew);
  }
}

TEST(Arena, ZeroInitialisesEveryAllocation) {
  StaticArena<256> storage;
  Arena& a = storage.arena();
  auto s = a.allocate<int>(16);
  ASSERT_TRUE(s.ok());
  for (int& v : *s) v = 99;
  a.reset();
  auto t = a.allocate<int>(16);
  ASSERT_TRUE(t.ok());
  for (int v : *t) EXPECT_EQ(v, 0);
}

// The uninitialised form takes the same room (its failure: below); in
// debug builds it fills the buffer with 0xA5 so a read-before-write shows.
TEST(Arena, UninitialisedAllocationAccountsAlikeAndIsPoisonedInDebug) {
  StaticArena<256> storage;
  Arena& a = storage.arena();
  ASSERT_TRUE(a.allocate<std::uint8_t>(3).ok());
  auto s = a.allocate_uninitialised<std::uint32_t>(8, "scratch row");
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(s->data()) % alignof(std::uint32_t), 0u);
  EXPECT_EQ(a.used(), 4u + 32u);
  EXPECT_EQ(s->size(), 8u);
#ifndef NDEBUG
  for (std::uint32_t v : *s) EXPECT_EQ(v, 0xA5A5A5A5u);
#endif
}

TEST(Arena, ExhaustionIsAnErrorNamingTheRequest) {
  StaticArena<64> storage;
  Arena& a = storage.arena();
  ASSERT_TRUE(a.allocate<std::uint8_t>(60).ok());
  auto r = a.allocate<std::uint32_t>(4, "disparity row");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.code(), Errc::capacity_exceeded);
  EXPECT_NE(std::strstr(r.error().message, "disparity row"), nullptr);
  EXPECT_EQ(a.used(), 60u);  // a failed request changes nothing
  auto u = a.allocate_uninitialised<std::uint32_t>(4, "cost row");
  EXPECT_EQ(u.code(), Errc::capacity_exceeded);
  EXPECT_NE(std::strstr(u.error().message, "cost row"), nullptr);
  EXPECT_EQ(a.used(), 60u);
}

TEST(Arena, HugeCountDoesNotOverflow) {
  StaticArena<64> storage;
  auto r = storage.arena().allocate<double>(SIZE_MAX / 4);
  EXPECT_EQ(r.code(), Errc::capacity_exceeded);
}

TEST(Arena, ScopeReleasesScratch) {
  StaticArena<256> storage;
  Arena& a = storage.arena();
  ASSERT_TRUE(a.allocate<int>(4).ok());
  {
    ArenaScope scratch(a);
    ASSERT_TRUE(a.allocate<int>(32).ok());
    EXPECT_EQ(a.used(), 16u + 128u);
  }
  EXPECT_EQ(a.used(), 16u);
  EXPECT_EQ(a.high_water(), 144u);
}

TEST(Arena, NoHeapInSteadyState) {
  static StaticArena<1 << 16> storage;
  Arena& a = storage.arena();
  test::HeapScope scope;
  for (int i = 0; i < 1000; ++i) {
    ArenaScope s(a);
    auto r = a.allocate<float>(1000);
    ASSERT_TRUE(r.ok());
    (*r)[999] = 1.0f;
  }
  EXPECT_EQ(scope.allocations(), 0u);
}

}  // namespace
}  // namespace petra
