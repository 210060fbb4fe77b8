#include "coupler/coupled_solvers/models/qr_factorization.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "coupler/coupled_solvers/models/linear_combination.hpp"

namespace cocopp {
namespace {

/// A column whose part orthogonal to the others is below this fraction of its norm is taken as
/// dependent: no update from it is accurate.
constexpr double kDependent = 1e-13;
/// Re-orthogonalise while a Gram-Schmidt pass removes more than this fraction of the norm
/// (Daniel-Gragg-Kaufman-Stewart): random or well-separated columns need one pass, nearly
/// dependent ones two, rarely three.
constexpr double kReorthogonalize = 0.7071067811865476;
constexpr int kMaxPasses = 3;

}  // namespace

void QrFactorization::clear() {
  ++version_;
  ++basis_generation_;
  basis_size_ = 0;
  u_.resize(0, 0);
  r_.resize(0, 0);
}

void QrFactorization::save_state(State& state) const {
  state.set("basis", Eigen::MatrixXd(basis()));
  state.set("basis_capacity", double(basis_.cols()));
  state.set("u", u_);
  state.set("r", r_);
}

void QrFactorization::load_state(const State& state, Eigen::Index rows, Eigen::Index columns) {
  ++version_;
  const Eigen::MatrixXd& basis = state.matrix("basis");
  const Eigen::MatrixXd& u = state.matrix("u");
  const Eigen::MatrixXd& r = state.matrix("r");
  const auto capacity = static_cast<Eigen::Index>(state.scalar("basis_capacity"));
  const Eigen::Index m = basis.cols();
  if ((m > 0 && basis.rows() != rows) || capacity < m || u.rows() != m || u.cols() != columns ||
      r.rows() != columns || r.cols() != columns)
    throw std::runtime_error("the saved QR factorization in '" + state.path() +
                             "' does not fit the saved secant columns (" + std::to_string(rows) +
                             " x " + std::to_string(columns) + ")");
  ++basis_generation_;
  basis_.resize(rows, capacity);
  basis_.leftCols(m) = basis;
  basis_size_ = m;
  u_ = u;
  r_ = r;
}

void QrFactorization::append_basis_vector(const Eigen::VectorXd& b) {
  if (basis_.rows() != b.size()) {  // first vector, or vectors of another length after clear()
    basis_.resize(b.size(), 0);
    basis_size_ = 0;
    ++basis_generation_;
  }
  if (basis_size_ == basis_.cols())
    basis_.conservativeResize(Eigen::NoChange, std::max<Eigen::Index>(8, 2 * basis_size_));
  basis_.col(basis_size_++) = b;
  u_.conservativeResize(basis_size_, Eigen::NoChange);
  u_.row(basis_size_ - 1).setZero();
}

bool QrFactorization::split(const Eigen::VectorXd& v, Split& result) {
  const double norm = v.norm();
  if (!(norm > 0.0)) return false;
  compact_if_wasteful();
  // Classical Gram-Schmidt against all of B (one matrix-vector product a pass).
  Eigen::VectorXd on_basis = Eigen::VectorXd::Zero(basis_size_);
  Eigen::VectorXd outside = v;
  double outside_norm = norm;
  for (int pass = 0; pass < kMaxPasses && basis_size_ > 0; ++pass) {
    const Eigen::VectorXd h = basis().transpose() * outside;
    add_linear_combination(outside, -h, [&](Eigen::Index j) { return basis_.col(j); });
    on_basis += h;
    const double previous = outside_norm;
    outside_norm = outside.norm();
    if (outside_norm >= kReorthogonalize * previous) break;
  }
  // v = Q on_q + B dead + outside, where dead lies in the directions of B not in Q. The same
  // split in the small space of B's coordinates, twice: cheap, and needed when v lies almost
  // in the span of Q.
  result.on_q = Eigen::VectorXd::Zero(columns());
  Eigen::VectorXd dead = on_basis;
  for (int pass = 0; pass < 2 && columns() > 0; ++pass) {
    const Eigen::VectorXd h = u_.transpose() * dead;
    dead.noalias() -= u_ * h;
    result.on_q += h;
  }
  result.rho = std::hypot(dead.norm(), outside_norm);
  if (result.rho <= kDependent * norm) return false;
  const bool grows = outside_norm > kDependent * norm;
  if (grows) append_basis_vector(outside / outside_norm);
  result.q_new = Eigen::VectorXd::Zero(basis_size_);
  result.q_new.head(dead.size()) = dead / result.rho;
  if (grows) result.q_new(basis_size_ - 1) = outside_norm / result.rho;
  return true;
}

bool QrFactorization::append(const Eigen::VectorXd& v) {
  Split s;
  if (!split(v, s)) return false;
  ++version_;
  const Eigen::Index k = columns();
  u_.conservativeResize(Eigen::NoChange, k + 1);
  u_.col(k) = s.q_new;
  r_.conservativeResize(k + 1, k + 1);
  r_.row(k).setZero();
  r_.col(k).head(k) = s.on_q;
  r_(k, k) = s.rho;
  return true;
}

bool QrFactorization::insert_front(const Eigen::VectorXd& v) {
  Split s;
  if (!split(v, s)) return false;
  ++version_;
  const Eigen::Index k = columns();
  // [v V] = [Q q] [on_q R; rho 0]: triangularise the first column from the bottom up.
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(k + 1, k + 1);
  r.col(0).head(k) = s.on_q;
  r(k, 0) = s.rho;
  r.block(0, 1, k, k) = r_;  // R moves one column right
  r_ = std::move(r);
  u_.conservativeResize(Eigen::NoChange, k + 1);
  u_.col(k) = s.q_new;
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
  // In place: a temporary column cost an allocation for each of an insertion's k rotations.
  double* left = u_.col(i).data();
  double* right = u_.col(i + 1).data();
  for (Eigen::Index row = 0; row < u_.rows(); ++row) {
    const double a = left[row], b = right[row];
    left[row] = c * a + s * b;
    right[row] = -s * a + c * b;
  }
}

void QrFactorization::remove(Eigen::Index j) {
  ++version_;
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
  u_.conservativeResize(Eigen::NoChange, k - 1);
}

void QrFactorization::remove_last() {
  ++version_;
  const Eigen::Index k = columns();
  r_.conservativeResize(k - 1, k - 1);
  u_.conservativeResize(Eigen::NoChange, k - 1);
}

void QrFactorization::compact_if_wasteful() {
  const Eigen::Index k = columns(), dead = basis_size_ - k;
  if (k == 0) {
    clear();
    return;
  }
  // Rebuilding costs one n x m x k product; it pays once the dead directions would slow every
  // projection down by a quarter.
  if (dead <= std::max<Eigen::Index>(8, k / 4)) return;
  const Eigen::MatrixXd q = basis() * u_;
  ++basis_generation_;
  ++version_;
  basis_.leftCols(k) = q;
  basis_size_ = k;
  u_ = Eigen::MatrixXd::Identity(k, k);
}

Eigen::VectorXd QrFactorization::project(const Eigen::VectorXd& b) const {
  if (columns() == 0) return Eigen::VectorXd();
  return u_.transpose() * (basis().transpose() * b);
}

Eigen::VectorXd QrFactorization::solve(const Eigen::VectorXd& b) const {
  return r_.triangularView<Eigen::Upper>().solve(project(b));
}

}  // namespace cocopp
