#include "algo/surface/fixed_point.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>

#include "algo/mesh/linalg3.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

using Q32 = Q31_32;

TEST(FixedPoint, ArithmeticRoundsToTheResolution) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1000.0, 1000.0);
  const double res = Q32::resolution().to_double();
  for (int i = 0; i < 10000; ++i) {
    const double a = u(rng), b = u(rng);
    const Q32 qa(a), qb(b);
    EXPECT_NEAR((qa + qb).to_double(), a + b, 2 * res);
    EXPECT_NEAR((qa - qb).to_double(), a - b, 2 * res);
    EXPECT_NEAR((qa * qb).to_double(), a * b, 2000 * res);
    if (std::abs(b) > 1e-3) {
      EXPECT_NEAR((qa / qb).to_double(), a / b, 1e-6 * std::abs(a / b) + 2e3 * res);
    }
  }
}

TEST(FixedPoint, SaturatesInsteadOfWrapping) {
  const Q32 big(2.0e9);
  EXPECT_EQ(big + big, Q32::max());
  EXPECT_EQ(-big - big, Q32::lowest());
  EXPECT_EQ(big * big, Q32::max());
  EXPECT_EQ(big * -big, Q32::lowest());
  EXPECT_EQ(Q32(1) / Q32(0), Q32::max());
  EXPECT_EQ(Q32(-1) / Q32(0), Q32::lowest());
  EXPECT_EQ(Q32(0) / Q32(0), Q32(0));
  EXPECT_EQ(Q32(1e30), Q32::max());
  EXPECT_EQ(-Q32::lowest(), Q32::max());  // symmetric range: negation never overflows
  EXPECT_TRUE(Q32::max().saturated());
  EXPECT_FALSE(isfinite(Q32::max()));
}

TEST(FixedPoint, SqrtAndLogMatchDouble) {
  for (double x : {1e-6, 0.001, 0.5, 1.0, 2.0, 3.14159, 100.0, 12345.678, 1.5e9}) {
    const double xq = Q32(x).to_double();  // the input as the format holds it
    EXPECT_NEAR(sqrt(Q32(x)).to_double(), std::sqrt(xq), 1e-9 * std::sqrt(xq) + 1e-9) << x;
    EXPECT_NEAR(log(Q32(x)).to_double(), std::log(xq), 1e-8) << x;
  }
  EXPECT_EQ(sqrt(Q32(-4)), Q32(0));
  EXPECT_EQ(log(Q32(0)), Q32::lowest());
  EXPECT_NEAR(log(Q47_16(0.25)).to_double(), std::log(0.25), 1e-4);
}

TEST(FixedPoint, WorksAsAnEigenScalarWithoutHeap) {
  test::HeapScope scope;
  Eigen::Matrix<Q32, 3, 3> m;
  m << Q32(2), Q32(1), Q32(0), Q32(1), Q32(3), Q32(1), Q32(0), Q32(1), Q32(4);
  const Eigen::Matrix<Q32, 3, 1> v(Q32(1), Q32(-2), Q32(0.5));
  const Eigen::Matrix<Q32, 3, 1> mv = m * v;
  EXPECT_NEAR(mv(0).to_double(), 0.0, 1e-9);
  EXPECT_NEAR(mv(1).to_double(), -4.5, 1e-9);
  EXPECT_NEAR(mv(2).to_double(), 0.0, 1e-9);
  EXPECT_NEAR(v.norm().to_double(), std::sqrt(5.25), 1e-9);
  EXPECT_NEAR(m.trace().to_double(), 9.0, 1e-12);
  const Ldlt3<Q32> f = ldlt3<Q32>(m);
  ASSERT_TRUE(f.positive);
  const Eigen::Matrix<Q32, 3, 1> x = f.solve(mv);
  EXPECT_LT((x - v).cwiseAbs().maxCoeff().to_double(), 1e-8);
  EXPECT_EQ(scope.allocations(), 0u);
}

}  // namespace
}  // namespace petra
