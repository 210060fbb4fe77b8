#pragma once
// Restarted GMRES (Saad & Schultz 1986) for a matrix-free operator on Eigen vectors.
//
// Used by ibqn, whose block operator is the identity minus a low-rank secant product: GMRES
// then converges in at most rank + 1 iterations, so it needs neither a preconditioner nor a
// matrix. The Arnoldi basis is orthogonalized twice with classical Gram-Schmidt ("twice is
// enough"), which keeps it orthogonal when the secant models are ill-conditioned; the least-
// squares problem is kept triangular with Givens rotations, so its residual is known at every
// iteration without solving it.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace cocopp {

struct GmresResult {
  Eigen::VectorXd x;
  int iterations = 0;              ///< Krylov iterations (operator applications) used
  double relative_residual = 0.0;  ///< ||b - A x|| / ||b|| of the returned x
  bool converged = false;          ///< relative_residual <= tolerance
};

namespace gmres_detail {

/// The rotated Hessenberg system of one GMRES cycle: H y ~ g, with H upper triangular after
/// the rotations and |g(k)| the residual norm after k iterations.
struct Cycle {
  Cycle(const Eigen::VectorXd& r0, double beta, int size)
      : basis(r0.size(), size + 1),
        h(Eigen::MatrixXd::Zero(size + 1, size)),
        g(Eigen::VectorXd::Zero(size + 1)),
        cosines(size),
        sines(size) {
    basis.col(0) = r0 / beta;
    g(0) = beta;
  }

  /// Orthogonalize w against the first k + 1 basis vectors into column k of h; returns false
  /// at a breakdown (w in their span: the Krylov space holds the solution).
  bool orthogonalize(Eigen::VectorXd& w, int k) {
    const double norm_in = w.norm();
    const auto previous = basis.leftCols(k + 1);
    for (int pass = 0; pass < 2; ++pass) {
      const Eigen::VectorXd coefficients = previous.transpose() * w;
      w.noalias() -= previous * coefficients;
      h.col(k).head(k + 1) += coefficients;
    }
    h(k + 1, k) = w.norm();
    if (h(k + 1, k) <= 16 * std::numeric_limits<double>::epsilon() * norm_in) return false;
    basis.col(k + 1) = w / h(k + 1, k);
    return true;
  }

  /// Apply the previous rotations to column k of h and make a new one that zeroes h(k+1, k).
  void rotate(int k) {
    for (int i = 0; i < k; ++i) {
      const double upper = h(i, k);
      h(i, k) = cosines(i) * upper + sines(i) * h(i + 1, k);
      h(i + 1, k) = -sines(i) * upper + cosines(i) * h(i + 1, k);
    }
    const double rho = std::hypot(h(k, k), h(k + 1, k));
    cosines(k) = rho > 0.0 ? h(k, k) / rho : 1.0;
    sines(k) = rho > 0.0 ? h(k + 1, k) / rho : 0.0;
    h(k, k) = rho;
    h(k + 1, k) = 0.0;
    g(k + 1) = -sines(k) * g(k);
    g(k) *= cosines(k);
  }

  /// The correction of the cycle after k iterations: basis y with H y = g.
  Eigen::VectorXd correction(int k) const {
    const Eigen::VectorXd y = h.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(g.head(k));
    return basis.leftCols(k) * y;
  }

  Eigen::MatrixXd basis;
  Eigen::MatrixXd h;
  Eigen::VectorXd g;
  Eigen::VectorXd cosines, sines;
};

}  // namespace gmres_detail

/// Solve A x = b, with `apply(v)` = A v, starting from x = 0, until ||b - A x|| <= tolerance
/// ||b|| or after `maximum_iterations` Krylov iterations, restarting every `restart`. The
/// returned x minimizes the residual over the last Krylov space even when not converged.
template <class Operator>
GmresResult gmres(Operator&& apply, const Eigen::VectorXd& b, double tolerance,
                  int maximum_iterations, int restart = 50) {
  GmresResult result;
  result.x = Eigen::VectorXd::Zero(b.size());
  const double b_norm = b.norm();
  if (b_norm == 0.0) {
    result.converged = true;
    return result;
  }
  const double target = tolerance * b_norm;
  Eigen::VectorXd r = b;
  double r_norm = b_norm;
  while (r_norm > target && result.iterations < maximum_iterations) {
    const int size = std::min(restart, maximum_iterations - result.iterations);
    gmres_detail::Cycle cycle(r, r_norm, size);
    int k = 0;
    bool breakdown = false;
    while (k < size && !breakdown && std::abs(cycle.g(k)) > target) {
      Eigen::VectorXd w = apply(Eigen::VectorXd(cycle.basis.col(k)));
      ++result.iterations;
      breakdown = !cycle.orthogonalize(w, k);
      cycle.rotate(k);
      ++k;
    }
    result.x += cycle.correction(k);
    // The true residual, not the recurrence's: restarts and the result must not drift.
    r = b - apply(result.x);
    r_norm = r.norm();
    if (breakdown) break;  // the Krylov space is exhausted: restarting cannot improve
  }
  result.relative_residual = r_norm / b_norm;
  result.converged = r_norm <= target;
  return result;
}

}  // namespace cocopp
