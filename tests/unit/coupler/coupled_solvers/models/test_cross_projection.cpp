// CrossProjection against its definition, Q_aᵀ D W_b: through R_a⁻¹ Q_aᵀ D W_b = V_a⁺ D W_b,
// the least-squares coefficients of a's fit for each weighted output column of b, while both
// models' columns come and go as in a run: new columns, filtered ones, aged ones, rebuilds of
// a's basis and a weight that changes.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "coupler/coupled_solvers/models/cross_projection.hpp"

using cocopp::CrossProjection;
using cocopp::SecantColumns;

namespace {

/// V_a⁺ diag(weights) W_b from scratch, by a dense QR of V_a.
Eigen::MatrixXd definition(const SecantColumns& a, const Eigen::VectorXd& weights,
                           const SecantColumns& b) {
  if (b.empty()) return Eigen::MatrixXd(a.size(), 0);
  Eigen::MatrixXd w = b.w_matrix();
  if (weights.size() > 0) w = weights.asDiagonal() * w;
  return a.v_matrix().colPivHouseholderQr().solve(w);
}

void expect_definition(CrossProjection& projection, const SecantColumns& a,
                       const Eigen::VectorXd& weights, const SecantColumns& b,
                       const std::string& when) {
  const Eigen::MatrixXd projected = projection.compute(a, weights, b);
  const Eigen::MatrixXd expected = definition(a, weights, b);
  ASSERT_EQ(projected.rows(), expected.rows()) << when;
  ASSERT_EQ(projected.cols(), expected.cols()) << when;
  if (expected.size() == 0) return;  // (Eigen's triangular solve reads an empty matrix's data)
  const Eigen::MatrixXd kept = a.qr().r().triangularView<Eigen::Upper>().solve(projected);
  EXPECT_LE((kept - expected).norm(), 1e-10 * expected.norm()) << when;
}

}  // namespace

TEST(CrossProjection, FollowsBothModelsColumnByColumn) {
  std::srand(5);
  const int n = 60;
  SecantColumns a, b;
  CrossProjection projection;
  const Eigen::VectorXd none;
  for (int step = 0; step < 12; ++step) {
    for (int iteration = 0; iteration < 4; ++iteration) {
      a.insert(Eigen::VectorXd::Random(n), Eigen::VectorXd::Random(n));
      expect_definition(projection, a, none, b, "a changed");
      b.insert(Eigen::VectorXd::Random(n), Eigen::VectorXd::Random(n));
      expect_definition(projection, a, none, b, "b changed");
      expect_definition(projection, a, none, b, "nothing changed");
    }
    // Reuse of 3 steps: the oldest columns go, and a's basis is rebuilt now and then.
    a.age_and_drop(3);
    b.age_and_drop(3);
    expect_definition(projection, a, none, b, "aged, step " + std::to_string(step));
  }
}

TEST(CrossProjection, FollowsFilteredColumnsAndChangedWeights) {
  std::srand(9);
  const int n = 30;
  SecantColumns a, b;
  CrossProjection projection;
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(n);
  for (int k = 0; k < 6; ++k) {
    a.insert(Eigen::VectorXd::Random(n), Eigen::VectorXd::Random(n));
    b.insert(Eigen::VectorXd::Random(n), Eigen::VectorXd::Random(n));
  }
  expect_definition(projection, a, weights, b, "weighted");
  // A column of a that repeats an earlier one is dropped, somewhere in the middle of V_a.
  a.insert(a.columns()[2].v, Eigen::VectorXd::Random(n));
  expect_definition(projection, a, weights, b, "dependent column dropped");
  // Automatic scaling fixes a weight late: everything kept is stale.
  weights.tail(n / 2).setConstant(1e-3);
  expect_definition(projection, a, weights, b, "weights changed");
  // More columns than rows in b: b filters; a unchanged keeps its coefficients.
  for (int k = 0; k < n + 2; ++k) b.insert(Eigen::VectorXd::Random(n), Eigen::VectorXd::Random(n));
  expect_definition(projection, a, weights, b, "b full");
}
