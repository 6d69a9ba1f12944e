#include "algo/core/fixed_vector.hpp"

#include <gtest/gtest.h>

namespace petra {
namespace {

TEST(FixedVector, PushUntilFullThenRefuses) {
  FixedVector<int, 3> v;
  EXPECT_TRUE(v.push_back(1));
  EXPECT_TRUE(v.push_back(2));
  EXPECT_TRUE(v.push_back(3));
  EXPECT_TRUE(v.full());
  EXPECT_FALSE(v.push_back(4));
  EXPECT_EQ(v.size(), 3u);
  EXPECT_EQ(v.back(), 3);
  int sum = 0;
  for (int x : v) sum += x;
  EXPECT_EQ(sum, 6);
}

TEST(FixedVector, ResizeWithinCapacity) {
  FixedVector<double, 4> v;
  EXPECT_TRUE(v.resize(2));
  EXPECT_EQ(v[1], 0.0);
  EXPECT_FALSE(v.resize(5));
  EXPECT_EQ(v.size(), 2u);
  v.pop_back();
  EXPECT_EQ(v.span().size(), 1u);
}

}  // namespace
}  // namespace petra
