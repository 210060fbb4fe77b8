#pragma once
// TubeStructure: the tube wall as a ring with inertia and bending, clamped at both ends
// (docs/tube-solvers.md):
//   rho_s h r'' + b1 r'''' - b2 r'' (in z) + b3 (r - r0) = p - p_ref.
// One coupling iteration takes the pressure (Pa) of the m cells and returns their radial
// displacement r_i - r0. The system matrix does not change, so it is factored once.
#include <Eigen/Dense>
#include <string>

#include "core/data/restart_file.hpp"
#include "solvers/tube/banded_solver.hpp"
#include "solvers/tube/tube_input.hpp"

namespace cocopp::tube {

enum class TimeScheme { kBackwardEuler, kNewmark };

struct TubeStructureParameters {
  TubeGeometry geometry;
  double rho_s = 0.0;  ///< wall density, kg/m^3
  double e = 0.0;      ///< Young's modulus, Pa
  double h = 0.0;      ///< wall thickness, m
  double nu = 0.0;     ///< Poisson's ratio
  double p_ref = 0.0;  ///< pressure at which the wall is undeformed, Pa
  TimeScheme time_scheme = TimeScheme::kBackwardEuler;
  double beta = 1.0;   ///< Newmark beta (1 for backward Euler)
  double gamma = 1.0;  ///< Newmark gamma (1 for backward Euler)
  /// Solver-coupling convergence: the largest residual of the wall equation (rows scaled to
  /// metres) at the previous iterate that counts as converged; 0 = not given.
  double residual_atol = 0.0;
  OutputSettings output;

  static TubeStructureParameters read(const Settings& input);
  static TubeStructureParameters load(const std::string& file);
};

class TubeStructure {
 public:
  /// The wall at rest (r = r0, no velocity or acceleration) at the end of `timestep_start`.
  TubeStructure(TubeStructureParameters parameters, double delta_t, int timestep_start = 0);

  void initialize_step();
  /// One coupling iteration: pressures (Pa) of the m cells -> radial displacements.
  Eigen::VectorXd solve(const Eigen::VectorXd& pressure);
  /// Solver-coupling convergence needs residual_atol: throws std::runtime_error without it.
  void start_reporting_convergence() const;
  /// The wall equation for the new pressure was met by the previous iterate within
  /// residual_atol: this solve changed nothing that matters (as CoCoNuT's ring model judges).
  bool converged_at_first_iteration() const { return converged_at_first_iteration_; }
  /// Commit the step: update the wall velocity and acceleration.
  void finalize_step();
  /// The ParaView file of `step` at `time` (s), if the output interval says so.
  void output_step(int step, double time) const;
  /// What a restart after this step needs, and back (`file` names the source in errors).
  RestartData restart_data() const;
  void restore(const RestartData& data, const std::filesystem::path& file);

  int step() const { return step_; }
  int cells() const { return cells_; }
  const TubeStructureParameters& parameters() const { return parameters_; }
  Eigen::VectorXd cell_centres() const { return parameters_.geometry.cell_centres(); }
  Eigen::VectorXd displacement() const;
  const Eigen::VectorXd& radial_velocity() const { return velocity_; }
  const Eigen::VectorXd& radial_acceleration() const { return acceleration_; }

  /// Coefficients of the wall equation.
  double b1() const { return b1_; }
  double b2() const { return b2_; }
  double b3() const { return b3_; }

 private:
  BandedMatrix assemble() const;
  double newmark_switch() const;

  TubeStructureParameters parameters_;
  double delta_t_;
  int step_;
  int cells_;
  double dz_;
  double r0_;
  double b1_, b2_, b3_;
  double diagonal_;               ///< C: every row is divided by it
  double neighbour_;              ///< coefficient of r_{i-1}, r_{i+1}
  double second_;                 ///< coefficient of r_{i-2}, r_{i+2}
  BandedMatrix matrix_{1, 0, 0};  ///< the system, for the residual at the previous iterate
  BandedLu lu_;
  bool converged_at_first_iteration_ = false;
  Eigen::VectorXd radius_, old_radius_;
  Eigen::VectorXd velocity_, old_velocity_;
  Eigen::VectorXd acceleration_, old_acceleration_;
  Eigen::VectorXd pressure_;
};

}  // namespace cocopp::tube
