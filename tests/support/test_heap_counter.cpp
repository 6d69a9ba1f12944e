// The heap counter must catch allocations, or every zero-heap test is hollow.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstdlib>
#include <memory>
#include <vector>

#include "tests/support/heap_counter.hpp"

namespace {

TEST(HeapCounter, SeesOperatorNew) {
  petra::test::HeapScope scope;
  auto p = std::make_unique<int>(7);
  EXPECT_EQ(*p, 7);
  EXPECT_GE(scope.allocations(), 1u);
}

TEST(HeapCounter, SeesVectorGrowth) {
  petra::test::HeapScope scope;
  std::vector<int> v;
  for (int i = 0; i < 100; ++i) v.push_back(i);
  EXPECT_GE(scope.allocations(), 1u);
}

TEST(HeapCounter, SeesMallocWhereReplaceable) {
  if (!petra::test::counts_malloc())
    GTEST_SKIP() << "skipped: the sanitizer runtime refused the allocation hook";
  petra::test::HeapScope scope;
  void* volatile p = std::malloc(64);
  std::free(p);
  EXPECT_EQ(scope.allocations(), 1u);
}

TEST(HeapCounter, QuietScopeCountsZero) {
  std::array<int, 64> a{};
  petra::test::HeapScope scope;
  for (int i = 0; i < 64; ++i) a[static_cast<std::size_t>(i)] = i * i;
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity() * 2.0;
  Eigen::Vector3d x = m.inverse() * Eigen::Vector3d(1, 2, 3);
  EXPECT_EQ(a[8], 64);
  EXPECT_DOUBLE_EQ(x.z(), 1.5);
  EXPECT_EQ(scope.allocations(), 0u);
}

#ifdef NDEBUG
// Eigen's own check is an eigen_assert, compiled out here: the counter must see it.
TEST(HeapCounter, SeesEigenDynamicAllocation) {
  if (!petra::test::counts_malloc())
    GTEST_SKIP() << "skipped: the sanitizer runtime refused the allocation hook";
  petra::test::HeapScope scope;
  Eigen::MatrixXd big(50, 50);
  big.setOnes();
  EXPECT_DOUBLE_EQ(big.sum(), 2500.0);
  EXPECT_GE(scope.allocations(), 1u);
}
#else
TEST(HeapCounterDeathTest, EigenDynamicAllocationAbortsInScope) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_DEATH(
      {
        petra::test::HeapScope scope;
        Eigen::MatrixXd big(50, 50);
        big.setOnes();
      },
      "heap allocation is forbidden");
}
#endif

}  // namespace
