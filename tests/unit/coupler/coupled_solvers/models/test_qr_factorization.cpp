// The updated QR factorization against its definition: V = Q R, Q^T Q = I, R upper triangular.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "coupler/coupled_solvers/models/qr_factorization.hpp"

using cocopp::QrFactorization;

namespace {

/// Rebuild V = Q R column by column from least-squares solves of unit right-hand sides is not
/// possible without Q, so check through solve(): for a full-rank V, solve(V e_j) = e_j and the
/// residual of solve(b) is orthogonal to every column of V.
void expect_factorizes(const QrFactorization& qr, const Eigen::MatrixXd& v) {
  ASSERT_EQ(qr.columns(), v.cols());
  for (Eigen::Index j = 0; j < v.cols(); ++j) {
    const Eigen::VectorXd c = qr.solve(v.col(j));
    EXPECT_TRUE(c.isApprox(Eigen::VectorXd::Unit(v.cols(), j), 1e-10)) << "column " << j;
  }
  const Eigen::VectorXd b = Eigen::VectorXd::Random(v.rows());
  const Eigen::VectorXd residual = b - v * qr.solve(b);
  EXPECT_LT((v.transpose() * residual).norm(), 1e-10 * b.norm());
  // |R_jj| equals the norm of column j's part orthogonal to the columns before it.
  for (Eigen::Index j = 1; j < v.cols(); ++j) {
    const Eigen::MatrixXd before = v.leftCols(j);
    const Eigen::VectorXd part = v.col(j) - before * before.colPivHouseholderQr().solve(v.col(j));
    EXPECT_NEAR(qr.diagonal(j), part.norm(), 1e-10 * v.col(j).norm()) << "column " << j;
  }
}

}  // namespace

TEST(QrFactorization, InsertFrontAppendAndRemoveKeepTheFactorization) {
  std::srand(7);
  const int n = 40;
  QrFactorization qr;
  Eigen::MatrixXd v(n, 0);
  auto insert_front = [&](const Eigen::VectorXd& column) {
    ASSERT_TRUE(qr.insert_front(column));
    Eigen::MatrixXd next(n, v.cols() + 1);
    next << column, v;
    v = next;
  };
  for (int i = 0; i < 8; ++i) insert_front(Eigen::VectorXd::Random(n));
  expect_factorizes(qr, v);

  qr.remove(3);  // a middle column
  Eigen::MatrixXd without(n, v.cols() - 1);
  without << v.leftCols(3), v.rightCols(v.cols() - 4);
  v = without;
  expect_factorizes(qr, v);

  qr.remove(0);  // the newest
  v = Eigen::MatrixXd(v.rightCols(v.cols() - 1));
  expect_factorizes(qr, v);

  qr.remove_last();  // the oldest
  v = Eigen::MatrixXd(v.leftCols(v.cols() - 1));
  expect_factorizes(qr, v);

  const Eigen::VectorXd extra = Eigen::VectorXd::Random(n);
  ASSERT_TRUE(qr.append(extra));
  Eigen::MatrixXd appended(n, v.cols() + 1);
  appended << v, extra;
  v = appended;
  expect_factorizes(qr, v);

  for (int i = 0; i < 30; ++i) {  // many updates: no drift
    insert_front(Eigen::VectorXd::Random(n));
    qr.remove(qr.columns() / 2);
    Eigen::MatrixXd shorter(n, v.cols() - 1);
    const Eigen::Index j = v.cols() / 2;
    shorter << v.leftCols(j), v.rightCols(v.cols() - j - 1);
    v = shorter;
  }
  expect_factorizes(qr, v);
}

TEST(QrFactorization, DependentColumnsAreRefused) {
  QrFactorization qr;
  const Eigen::VectorXd a = Eigen::VectorXd::Random(5), b = Eigen::VectorXd::Random(5);
  ASSERT_TRUE(qr.insert_front(a));
  ASSERT_TRUE(qr.insert_front(b));
  EXPECT_FALSE(qr.insert_front(2.0 * a - b));
  EXPECT_FALSE(qr.append(Eigen::VectorXd::Zero(5)));
  EXPECT_EQ(qr.columns(), 2);
}

// The way `ls` with reuse drives it: a few columns in front every step, the oldest dropped at
// the back, for many steps. Dead directions pile up and the basis is rebuilt now and then;
// the factorization must stay exact throughout, also when the columns outnumber the rows.
TEST(QrFactorization, StaysExactOverManyStepsOfInsertFrontAndRemoveLast) {
  std::srand(11);
  for (const int n : {12, 60}) {
    QrFactorization qr;
    Eigen::MatrixXd v(n, 0);
    for (int step = 0; step < 40; ++step) {
      for (int i = 0; i < 4; ++i) {
        const Eigen::VectorXd column = Eigen::VectorXd::Random(n);
        if (!qr.insert_front(column)) continue;  // more columns than rows
        Eigen::MatrixXd next(n, v.cols() + 1);
        next << column, v;
        v = next;
      }
      while (v.cols() > 10) {
        qr.remove_last();
        v = Eigen::MatrixXd(v.leftCols(v.cols() - 1));
      }
      if (step % 3 == 1 && v.cols() > 2) {  // a filtered middle column now and then
        qr.remove(1);
        Eigen::MatrixXd shorter(n, v.cols() - 1);
        shorter << v.leftCols(1), v.rightCols(v.cols() - 2);
        v = shorter;
      }
      SCOPED_TRACE("n " + std::to_string(n) + ", step " + std::to_string(step));
      expect_factorizes(qr, v);
      if (::testing::Test::HasFailure()) return;
    }
  }
}
