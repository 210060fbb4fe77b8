#pragma once
// ReynoldsFilm: how a thin lubricant film's pressure answers a change of its gap, for the
// displacement drive's Newton step (`film_stiffness: reynolds`, docs/solver-wrappers-
// calculix.md). A film's pressure is not local: a thinner gap near the outlet cuts the flow
// rate and raises the pressure over the whole inlet, and a structure driven under it sees
// that as a stiffness between distant lines that a local 2 p / gap per line misses.
//
// The model: Reynolds' equation for a film between a wall sliding along the chain of faces and
// a fixed one, ambient pressure at both ends of the chain, steady, Newtonian:
//   dp/dz = 6 eta U / h^2 - 12 eta q / h^3,  q the same everywhere,
// on cells (the faces, in order along the sliding direction) whose gap varies linearly
// between their centres, which integrates exactly. eta U is unknown to the structure's
// wrapper, and so is the sliding direction: both come from fitting the model's pressure to
// the film's own (least squares over the faces' lengths), which also absorbs what the model
// leaves out (the film's inertia, a gap not thin everywhere). The fit's misfit is kept for
// messages.
#include <Eigen/Core>

namespace cocopp::calculix {

class ReynoldsFilm {
 public:
  /// The chain: each face's axial position (its centre), length and gap, in order of
  /// position; `pressure` the film's own at the faces. Throws std::invalid_argument for a
  /// chain the model cannot take (fewer than two faces, a gap <= 0, positions not rising).
  ReynoldsFilm(Eigen::VectorXd position, Eigen::VectorXd length, Eigen::VectorXd gap,
               const Eigen::VectorXd& pressure);

  /// The model's pressure at the faces, scaled to the film's.
  Eigen::VectorXd pressure() const { return scale_ * shape(gap_); }
  /// d p_f / d h_g (Pa/m), the model's, scaled.
  Eigen::MatrixXd pressure_gradient() const;
  /// ||p_film - p_model|| / ||p_film||, length-weighted (0: the model fits exactly).
  double misfit() const { return misfit_; }

 private:
  /// The model's pressure for 6 eta U = 1 along increasing position.
  Eigen::VectorXd shape(const Eigen::VectorXd& gap) const;

  Eigen::VectorXd position_, length_, gap_;
  double scale_ = 0.0, misfit_ = 1.0;
};

}  // namespace cocopp::calculix
