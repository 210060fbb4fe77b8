#pragma once
// CrossProjection: Q_aᵀ D W_b, the output columns W_b of one least-squares model, weighted by D
// as a's inputs are, in the orthonormal basis Q_a of another's fit (V_a = Q_a R_a). It is the
// middle of the product of the two models' Jacobians, W_a R_a⁻¹ (Q_aᵀ D W_b) R_b⁻¹ Q_bᵀ D',
// with which ibqn solves its block equations in the small space of the columns.
//
// Why it is kept rather than formed: forming it costs n k_a k_b, a GEMM over the interface,
// twice per coupling iteration. It is kept at two levels, both with one column per column of
// b (known by its id), so that an iteration computes only what changed:
// - P = B_aᵀ D W_b (Q_a = B_a U_a, and B_a only grows between rebuilds): a row for each new
//   basis vector of a and a column for each new column of b, O(n k);
// - U_aᵀ P: while a's factorization is unchanged only b's new columns, otherwise all of them,
//   O(k³) without touching the interface.
// A rebuild of B_a or a change of D (a weight fixed late by automatic scaling) starts afresh.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "coupler/coupled_solvers/models/secant_columns.hpp"

namespace cocopp {

class CrossProjection {
 public:
  /// Q_aᵀ diag(weights) W_b (k_a x k_b) for the current columns of a and b; empty weights
  /// mean all ones.
  Eigen::MatrixXd compute(const SecantColumns& a, const Eigen::VectorXd& weights,
                          const SecantColumns& b);

 private:
  /// basisᵀ D w.
  template <class Basis>
  Eigen::VectorXd project(const Basis& basis, const Eigen::VectorXd& w) const;
  /// Whether P must be started afresh for a's basis and these weights.
  bool stale(const QrFactorization& qr, const Eigen::VectorXd& weights) const;

  Eigen::MatrixXd basis_products_;  ///< P = B_aᵀ D W_b for the columns ids_
  Eigen::MatrixXd projections_;     ///< U_aᵀ P for the columns ids_
  std::vector<std::uint64_t> ids_;  ///< the columns of b, in the order of the two matrices
  std::uint64_t generation_ = 0;    ///< of a's basis when basis_products_ was made
  std::uint64_t version_ = 0;       ///< of a's factorization when projections_ were made
  Eigen::VectorXd weights_;         ///< D when basis_products_ was made
  bool valid_ = false;
};

}  // namespace cocopp
