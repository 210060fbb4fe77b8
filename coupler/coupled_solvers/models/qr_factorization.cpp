#include "coupler/coupled_solvers/models/qr_factorization.hpp"

#include <cmath>

namespace cocopp {

void QrFactorization::clear() {
  q_.clear();
  r_.resize(0, 0);
}

bool QrFactorization::orthogonalize(const Eigen::VectorXd& v, Eigen::VectorXd& w,
                                    Eigen::VectorXd& rest) const {
  // Classical Gram-Schmidt with one re-orthogonalisation: as accurate as Householder here.
  const Eigen::Index k = columns();
  w = Eigen::VectorXd::Zero(k);
  rest = v;
  for (int pass = 0; pass < 2; ++pass)
    for (Eigen::Index i = 0; i < k; ++i) {
      const double h = q_[std::size_t(i)].dot(rest);
      rest -= h * q_[std::size_t(i)];
      w(i) += h;
    }
  const double norm = v.norm();
  return norm > 0.0 && rest.norm() > 1e-13 * norm;
}

bool QrFactorization::append(const Eigen::VectorXd& v) {
  Eigen::VectorXd w, rest;
  if (!orthogonalize(v, w, rest)) return false;
  const Eigen::Index k = columns();
  const double rho = rest.norm();
  r_.conservativeResize(k + 1, k + 1);
  r_.row(k).setZero();
  r_.col(k).head(k) = w;
  r_(k, k) = rho;
  q_.push_back(rest / rho);
  return true;
}

bool QrFactorization::insert_front(const Eigen::VectorXd& v) {
  Eigen::VectorXd w, rest;
  if (!orthogonalize(v, w, rest)) return false;
  const Eigen::Index k = columns();
  const double rho = rest.norm();
  // [v V] = [Q q] [w R; rho 0]: triangularise the first column from the bottom up.
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(k + 1, k + 1);
  r.col(0).head(k) = w;
  r(k, 0) = rho;
  r.block(0, 1, k, k) = r_;  // R moves one column right
  r_ = std::move(r);
  q_.push_back(rest / rho);
  for (Eigen::Index i = k; i > 0; --i) {
    const double a = r_(i - 1, 0), b = r_(i, 0);
    const double h = std::hypot(a, b);
    if (h == 0.0) continue;
    rotate(i - 1, a / h, b / h, 0);
    r_(i, 0) = 0.0;
  }
  return true;
}

void QrFactorization::rotate(Eigen::Index i, double c, double s, Eigen::Index from) {
  const Eigen::Index k = r_.cols();
  for (Eigen::Index j = from; j < k; ++j) {
    const double upper = r_(i, j), lower = r_(i + 1, j);
    r_(i, j) = c * upper + s * lower;
    r_(i + 1, j) = -s * upper + c * lower;
  }
  Eigen::VectorXd& left = q_[i];
  Eigen::VectorXd& right = q_[i + 1];
  const Eigen::VectorXd old_left = left;
  left = c * left + s * right;
  right = -s * old_left + c * right;
}

void QrFactorization::remove(Eigen::Index j) {
  const Eigen::Index k = columns();
  // Delete column j of R: the columns after it become upper Hessenberg; rotate it back.
  Eigen::MatrixXd r(k, k - 1);
  r.leftCols(j) = r_.leftCols(j);
  r.rightCols(k - 1 - j) = r_.rightCols(k - 1 - j);
  r_ = std::move(r);
  for (Eigen::Index i = j; i < k - 1; ++i) {
    const double a = r_(i, i), b = r_(i + 1, i);
    const double h = std::hypot(a, b);
    if (h == 0.0) continue;
    rotate(i, a / h, b / h, i);
    r_(i + 1, i) = 0.0;
  }
  // The last row of a k x (k-1) upper triangular matrix is zero: drop it with its Q column.
  r_.conservativeResize(k - 1, k - 1);
  q_.pop_back();
}

void QrFactorization::remove_last() {
  const Eigen::Index k = columns();
  r_.conservativeResize(k - 1, k - 1);
  q_.pop_back();
}

Eigen::VectorXd QrFactorization::solve(const Eigen::VectorXd& b) const {
  const Eigen::Index k = columns();
  Eigen::VectorXd qtb(k);
  for (Eigen::Index i = 0; i < k; ++i) qtb(i) = q_[i].dot(b);
  return r_.triangularView<Eigen::Upper>().solve(qtb);
}

}  // namespace cocopp
