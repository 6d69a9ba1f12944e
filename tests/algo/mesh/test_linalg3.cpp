#include "algo/mesh/linalg3.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <random>

#include "algo/surface/fixed_point.hpp"

namespace petra {
namespace {

Eigen::Matrix3d random_spd(std::mt19937_64& rng, double cond) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Matrix3d r =
      Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
  const Eigen::Vector3d ev(1.0, std::sqrt(cond), cond);
  return r * ev.asDiagonal() * r.transpose();
}

TEST(Linalg3, LdltSolvesAndGivesLogDetAndMahalanobis) {
  std::mt19937_64 rng(1);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Matrix3d a = random_spd(rng, 1e4);
    const Eigen::Vector3d b = Eigen::Vector3d::Random();
    const Ldlt3<double> f = ldlt3<double>(a);
    ASSERT_TRUE(f.positive);
    EXPECT_LT((a * f.solve(b) - b).norm(), 1e-10);
    EXPECT_NEAR(f.log_det(), std::log(a.determinant()), 1e-10);
    EXPECT_NEAR(f.mahalanobis(b), b.dot(a.inverse() * b), 1e-8 * b.dot(a.inverse() * b));
  }
}

TEST(Linalg3, LdltReportsASingularMatrix) {
  Eigen::Matrix3d a;
  a << 1, 2, 3, 2, 4, 6, 3, 6, 9;  // rank 1
  EXPECT_FALSE(ldlt3<double>(a).positive);
  EXPECT_FALSE(ldlt3<double>(Eigen::Matrix3d::Zero()).positive);
}

TEST(Linalg3, JacobiMatchesEigenSolver) {
  std::mt19937_64 rng(2);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Matrix3d a = random_spd(rng, 1e6);
    const SymEigen3<double> e = sym_eigen3<double>(a);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> ref(a);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(e.values(k), ref.eigenvalues()(k), 1e-9 * ref.eigenvalues()(2));
      EXPECT_LT((a * e.vectors.col(k) - e.values(k) * e.vectors.col(k)).norm(), 1e-9 * 1e6);
    }
    EXPECT_LT((e.vectors.transpose() * e.vectors - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  }
}

TEST(Linalg3, JacobiInFixedPointFindsTheSmallestAxis) {
  std::mt19937_64 rng(3);
  for (int i = 0; i < 50; ++i) {
    const Eigen::Matrix3d a = random_spd(rng, 1e3);
    const SymEigen3<Q31_32> e = sym_eigen3<Q31_32>(a.cast<Q31_32>());
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> ref(a);
    const Eigen::Vector3d v0 = e.vectors.col(0).cast<double>();
    EXPECT_NEAR(v0.norm(), 1.0, 1e-8);  // rotations accumulate rounding in the norm only
    const double sin_angle = v0.normalized().cross(ref.eigenvectors().col(0)).norm();
    EXPECT_LT(sin_angle, 1e-7);
    // Entries up to 1e3 at a resolution of 2.3e-10: ~1e-9 relative.
    EXPECT_NEAR(e.values(0).to_double(), ref.eigenvalues()(0), 1e-9 * ref.eigenvalues()(2));
  }
}

}  // namespace
}  // namespace petra
