// BandedLu against Eigen's dense LU on random banded matrices.
#include <gtest/gtest.h>

#include <random>

#include "solvers/tube/banded_solver.hpp"

namespace cocopp::tube {
namespace {

BandedMatrix random_banded(int size, int lower, int upper, std::mt19937& random,
                           double diagonal_boost) {
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  BandedMatrix matrix(size, lower, upper);
  for (int i = 0; i < size; ++i) {
    for (int j = std::max(0, i - lower); j <= std::min(size - 1, i + upper); ++j) {
      matrix(i, j) = value(random) + (i == j ? diagonal_boost : 0.0);
    }
  }
  return matrix;
}

double relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).norm() / b.norm();
}

// Eigen's estimate of the 1-norm condition number.
double condition_number(const Eigen::MatrixXd& dense) {
  return 1.0 / dense.partialPivLu().rcond();
}

TEST(BandedSolver, MatchesDenseSolveOnRandomMatrices) {
  std::mt19937 random(42);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  int compared = 0;
  for (int lower : {0, 1, 2, 4}) {
    for (int upper : {0, 1, 3, 4}) {
      for (int size : {1, 5, 9, 40, 204}) {
        // Random entries without diagonal dominance, so partial pivoting swaps rows most of the
        // time. Triangular matrices cannot pivot and random ones are exponentially
        // ill-conditioned: give them a dominant diagonal.
        const bool triangular = lower == 0 || upper == 0;
        const BandedMatrix matrix =
            random_banded(size, lower, upper, random, triangular ? 3.0 : 0.0);
        const Eigen::VectorXd rhs =
            Eigen::VectorXd::NullaryExpr(size, [&] { return value(random); });
        const Eigen::MatrixXd dense = matrix.to_dense();
        const Eigen::VectorXd solution = solve_banded(matrix, rhs);
        // Backward stable: a small residual whatever the conditioning.
        EXPECT_LT((dense * solution - rhs).norm(), 1e-13 * dense.norm() * solution.norm())
            << "size " << size << ", lower " << lower << ", upper " << upper;
        const double condition = condition_number(dense);
        if (condition > 1e8) continue;  // the dense solution itself is inaccurate then
        const Eigen::VectorXd expected = dense.fullPivLu().solve(rhs);
        EXPECT_LT(relative_difference(solution, expected), 1e-15 * condition + 1e-14)
            << "size " << size << ", lower " << lower << ", upper " << upper << ", condition "
            << condition;
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 70);  // of 80: nearly all random matrices are well enough conditioned
}

TEST(BandedSolver, PivotsWhenTheDiagonalIsZero) {
  // A zero (1, 1) entry after elimination would break LU without pivoting.
  BandedMatrix matrix(4, 1, 1);
  const double entries[4][4] = {{0, 2, 0, 0}, {1, 0, 3, 0}, {0, 4, 0, 5}, {0, 0, 6, 1}};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      if (matrix.in_band(i, j)) matrix(i, j) = entries[i][j];
    }
  }
  const Eigen::VectorXd rhs = Eigen::Vector4d(1, 2, 3, 4);
  const Eigen::VectorXd expected = matrix.to_dense().partialPivLu().solve(rhs);
  EXPECT_LT(relative_difference(solve_banded(matrix, rhs), expected), 1e-14);
}

TEST(BandedSolver, OneFactorisationSolvesManyRightHandSides) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  const BandedMatrix matrix = random_banded(204, 4, 4, random, 0.0);
  const BandedLu lu(matrix);
  for (int k = 0; k < 5; ++k) {
    const Eigen::VectorXd rhs = Eigen::VectorXd::NullaryExpr(204, [&] { return value(random); });
    const Eigen::VectorXd solution = lu.solve(rhs);
    EXPECT_LT((matrix.multiply(solution) - rhs).norm() / rhs.norm(), 1e-10);
  }
}

TEST(BandedSolver, SingularMatrixThrows) {
  BandedMatrix matrix(3, 1, 1);
  matrix(0, 0) = 1.0;
  matrix(1, 0) = 1.0;  // column 1 and 2 are zero below row 0
  EXPECT_THROW(BandedLu{matrix}, std::runtime_error);
}

TEST(BandedSolver, EntriesOutsideTheBandAreRejected) {
  BandedMatrix matrix(5, 1, 2);
  EXPECT_NO_THROW(matrix(0, 2) = 1.0);
  EXPECT_THROW(matrix(0, 3) = 1.0, std::out_of_range);
  EXPECT_THROW(matrix(2, 0) = 1.0, std::out_of_range);
}

}  // namespace
}  // namespace cocopp::tube
