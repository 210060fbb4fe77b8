#pragma once
// Thin QR factorization V = Q R of a tall matrix whose columns are inserted at the front
// (newest first) and removed anywhere, as the least-squares secant models need.
//
// Updates cost O(n k) instead of the O(n k^2) of a new factorization, which matters because a
// quasi-Newton model changes V in every coupling iteration. For large interfaces (n = 1e5,
// k = 100: Q alone is 80 MB) the cost is memory traffic, so Q is never rewritten: it is kept as
// Q = B U, with B (n x m) an orthonormal basis that only grows by appending and U (m x k) a
// small matrix with orthonormal columns. The Givens rotations that keep R triangular act on U
// alone. Removing a column leaves a direction of B unused; B is rebuilt (B <- B U, U <- I)
// only when such dead directions make up a sizeable part of it.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>

#include "coupler/results/state.hpp"

namespace cocopp {

class QrFactorization {
 public:
  Eigen::Index columns() const { return r_.cols(); }
  void clear();

  /// V <- [v V]. Returns false (and changes nothing) if v lies numerically in the span of the
  /// current columns, where no update is accurate: the caller then factorizes anew.
  bool insert_front(const Eigen::VectorXd& v);
  /// V <- [V v] (v becomes the last, oldest column). Same return value as insert_front.
  bool append(const Eigen::VectorXd& v);
  /// Remove column j of V.
  void remove(Eigen::Index j);
  /// Remove the last (oldest) column of V.
  void remove_last();

  /// |R_jj|: the part of column j not in the span of the columns before it.
  double diagonal(Eigen::Index j) const { return std::abs(r_(j, j)); }
  /// The factors, Q = basis() u() and V = Q r(), for products formed outside (CrossProjection).
  Eigen::Ref<const Eigen::MatrixXd> basis() const { return basis_.leftCols(basis_size_); }
  const Eigen::MatrixXd& u() const { return u_; }
  const Eigen::MatrixXd& r() const { return r_; }
  /// Changes whenever vectors already in basis() change (rebuild, clear, load); appending a
  /// vector keeps it, so that products with the basis can be extended rather than redone.
  std::uint64_t basis_generation() const { return basis_generation_; }
  /// Changes with every change of the factorization (each public call that changes it counts
  /// once; the private steps it is made of do not).
  std::uint64_t version() const { return version_; }

  /// c = argmin ||V c - b||.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  /// Q^T b (k values).
  Eigen::VectorXd project(const Eigen::VectorXd& b) const;

  /// The factors as they are (B with its capacity, U, R): a factorization rebuilt from V
  /// differs in round-off, and a restarted run is to continue bit for bit.
  void save_state(State& state) const;
  /// Takes the factors save_state() wrote, for a V of `columns` columns of length `rows`;
  /// throws std::runtime_error naming the state path if they do not fit.
  void load_state(const State& state, Eigen::Index rows, Eigen::Index columns);

 private:
  /// A new column v split into its coefficients on Q and the rest, q_new * rho, orthogonal
  /// to Q; q_new is given by its coordinates in B (after B has grown if it had to).
  struct Split {
    Eigen::VectorXd on_q;   ///< k coefficients
    Eigen::VectorXd q_new;  ///< coordinates of the new orthonormal column in B
    double rho = 0.0;
  };
  /// Returns false if the rest is numerically zero (v depends on the columns of V).
  bool split(const Eigen::VectorXd& v, Split& result);
  void append_basis_vector(const Eigen::VectorXd& b);
  /// Drop the dead directions of B when they are many: B <- B U, U <- I.
  void compact_if_wasteful();
  /// Apply the rotation [c s; -s c] to columns i and i + 1 of Q, i.e. of U (and to rows i,
  /// i + 1 of R from column `from` on), so that V = Q R stays true.
  void rotate(Eigen::Index i, double c, double s, Eigen::Index from);

  Eigen::MatrixXd basis_;        ///< B in its first basis_size_ columns; spare capacity after
  Eigen::Index basis_size_ = 0;  ///< m
  Eigen::MatrixXd u_;            ///< m x k, orthonormal columns: Q = B U
  Eigen::MatrixXd r_;            ///< k x k, upper triangular
  std::uint64_t basis_generation_ = 0;
  std::uint64_t version_ = 0;
};

}  // namespace cocopp
