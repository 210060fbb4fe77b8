#include "coupler/coupled_solvers/models/cross_projection.hpp"

#include <algorithm>

namespace cocopp {

template <class Basis>
Eigen::VectorXd CrossProjection::project(const Basis& basis, const Eigen::VectorXd& w) const {
  // Unweighted (scaling off), w is used in place: no copy of an interface-sized vector.
  if (weights_.size() == 0) return basis.transpose() * w;
  return basis.transpose() * w.cwiseProduct(weights_);
}

bool CrossProjection::stale(const QrFactorization& qr, const Eigen::VectorXd& weights) const {
  return !valid_ || qr.basis_generation() != generation_ ||
         qr.basis().cols() < basis_products_.rows() || weights.size() != weights_.size() ||
         weights != weights_;
}

Eigen::MatrixXd CrossProjection::compute(const SecantColumns& a, const Eigen::VectorXd& weights,
                                         const SecantColumns& b) {
  const QrFactorization& qr = a.qr();
  const auto basis = qr.basis();
  const bool fresh = stale(qr, weights);
  if (fresh) {
    ids_.clear();
    weights_ = weights;
    generation_ = qr.basis_generation();
    valid_ = true;
  }
  const bool same_factorization = !fresh && qr.version() == version_;
  const Eigen::Index m = basis.cols(), known_rows = fresh ? 0 : basis_products_.rows();
  const auto& columns = b.columns();
  const auto k_b = Eigen::Index(columns.size());
  Eigen::MatrixXd products(m, k_b);
  Eigen::MatrixXd projections(qr.columns(), k_b);
  std::vector<std::uint64_t> ids(columns.size());
  for (Eigen::Index j = 0; j < k_b; ++j) {
    const auto& column = columns[std::size_t(j)];
    ids[std::size_t(j)] = column.id;
    const auto found = std::find(ids_.begin(), ids_.end(), column.id);
    const Eigen::Index known = found == ids_.end() ? -1 : Eigen::Index(found - ids_.begin());
    if (known < 0) {
      products.col(j) = project(basis, column.w);
    } else {
      products.col(j).head(known_rows) = basis_products_.col(known).head(known_rows);
      if (m > known_rows)  // rows for the basis vectors a gained since
        products.col(j).tail(m - known_rows) = project(basis.rightCols(m - known_rows), column.w);
    }
    if (same_factorization && known >= 0)
      projections.col(j) = projections_.col(known);
    else if (same_factorization)
      projections.col(j) = qr.u().transpose() * products.col(j);
  }
  if (!same_factorization) projections = qr.u().transpose() * products;
  basis_products_ = std::move(products);
  projections_ = std::move(projections);
  ids_ = std::move(ids);
  version_ = qr.version();
  return projections_;
}

}  // namespace cocopp
