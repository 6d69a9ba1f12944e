#include "algo/surface/fixed_point.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>

#include "algo/mesh/linalg3.hpp"
#include "tests/support/heap_counter.hpp"

namespace petra {
namespace {

using Q = Q31_32;

TEST(FixedPoint, ArithmeticRoundsToTheResolution) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1000.0, 1000.0);
  const double res = Q::resolution().to_double();
  for (int i = 0; i < 10000; ++i) {
    const double a = u(rng), b = u(rng);
    const Q qa(a), qb(b);
    EXPECT_NEAR((qa + qb).to_double(), a + b, 2 * res);
    EXPECT_NEAR((qa - qb).to_double(), a - b, 2 * res);
    EXPECT_NEAR((qa * qb).to_double(), a * b, 2000 * res);
    if (std::abs(b) > 1e-3) {
      EXPECT_NEAR((qa / qb).to_double(), a / b, 1e-6 * std::abs(a / b) + 2e3 * res);
    }
  }
}

TEST(FixedPoint, SaturatesInsteadOfWrapping) {
  const Q big(2.0e9);
  EXPECT_EQ(big + big, Q::max());
  EXPECT_EQ(-big - big, Q::lowest());
  EXPECT_EQ(big * big, Q::max());
  EXPECT_EQ(big * -big, Q::lowest());
  EXPECT_EQ(Q(1) / Q(0), Q::max());
  EXPECT_EQ(Q(-1) / Q(0), Q::lowest());
  EXPECT_EQ(Q(0) / Q(0), Q(0));
  EXPECT_EQ(Q(1e30), Q::max());
  EXPECT_EQ(-Q::lowest(), Q::max());  // symmetric range: negation never overflows
  EXPECT_TRUE(Q::max().saturated());
  EXPECT_FALSE(isfinite(Q::max()));
}

TEST(FixedPoint, SqrtAndLogMatchDouble) {
  for (double x : {1e-6, 0.001, 0.5, 1.0, 2.0, 3.14159, 100.0, 12345.678, 1.5e9}) {
    const double xq = Q(x).to_double();  // the input as the format holds it
    EXPECT_NEAR(sqrt(Q(x)).to_double(), std::sqrt(xq), 1e-9 * std::sqrt(xq) + 1e-9) << x;
    EXPECT_NEAR(log(Q(x)).to_double(), std::log(xq), 1e-8) << x;
  }
  EXPECT_EQ(sqrt(Q(-4)), Q(0));
  EXPECT_EQ(log(Q(0)), Q::lowest());
  EXPECT_NEAR(log(Q47_16(0.25)).to_double(), std::log(0.25), 1e-4);
}

TEST(FixedPoint, WorksAsAnEigenScalarWithoutHeap) {
  test::HeapScope scope;
  Eigen::Matrix<Q, 3, 3> m;
  m << Q(2), Q(1), Q(0), Q(1), Q(3), Q(1), Q(0), Q(1), Q(4);
  const Eigen::Matrix<Q, 3, 1> v(Q(1), Q(-2), Q(0.5));
  const Eigen::Matrix<Q, 3, 1> mv = m * v;
  EXPECT_NEAR(mv(0).to_double(), 0.0, 1e-9);
  EXPECT_NEAR(mv(1).to_double(), -4.5, 1e-9);
  EXPECT_NEAR(mv(2).to_double(), 0.0, 1e-9);
  EXPECT_NEAR(v.norm().to_double(), std::sqrt(5.25), 1e-9);
  EXPECT_NEAR(m.trace().to_double(), 9.0, 1e-12);
  const Ldlt3<Q> f = ldlt3<Q>(m);
  ASSERT_TRUE(f.positive);
  const Eigen::Matrix<Q, 3, 1> x = f.solve(mv);
  EXPECT_LT((x - v).cwiseAbs().maxCoeff().to_double(), 1e-8);
  EXPECT_EQ(scope.allocations(), 0u);
}

}  // namespace
}  // namespace petra
