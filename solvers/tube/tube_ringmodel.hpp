#pragma once
// TubeRingmodel: the tube wall as independent massless rings (docs/tube-solvers.md). The
// cross-section follows from the local pressure alone (a tube law), so there is no state:
// one coupling iteration maps the pressure (Pa) of the m cells to their radial displacement.
#include <Eigen/Dense>
#include <string>

#include "core/data/restart_file.hpp"
#include "solvers/tube/tube_input.hpp"

namespace cocopp::tube {

struct TubeRingmodelParameters {
  TubeGeometry geometry;
  double rho_f = 0.0;  ///< fluid density, kg/m^3 (the tube law is written in p / rho_f)
  double e = 0.0;      ///< Young's modulus, Pa
  double h = 0.0;      ///< wall thickness, m
  double p_ref = 0.0;  ///< pressure at which the wall is undeformed, Pa
  /// Solver-coupling convergence: the largest change of the displacement (2-norm, m) that
  /// counts as converged; 0 = not given.
  double residual_atol = 0.0;
  OutputSettings output;

  /// Moens-Korteweg wave speed squared, E h / (rho_f d).
  double wave_speed_squared() const;

  static TubeRingmodelParameters read(const Settings& input);
  static TubeRingmodelParameters load(const std::string& file);
};

class TubeRingmodel {
 public:
  /// Throws std::invalid_argument if p_ref leaves no positive c0^2 = cmk2 - p_ref / (2 rho_f).
  explicit TubeRingmodel(TubeRingmodelParameters parameters, int timestep_start = 0);

  void initialize_step() { ++step_; }
  /// Pressures (Pa) -> radial displacements. Throws std::runtime_error("unphysical pressure
  /// ...") where p / rho_f >= 2 c0^2 + p_ref / rho_f (the tube law has no finite area there).
  Eigen::VectorXd solve(const Eigen::VectorXd& pressure);
  void finalize_step() {}
  /// Solver-coupling convergence needs residual_atol: throws std::runtime_error without it.
  void start_reporting_convergence() const;
  /// The previous displacement already met the tube law for the new pressure within
  /// residual_atol (CoCoNuT's ring model judges its areas alike).
  bool converged_at_first_iteration() const { return converged_at_first_iteration_; }
  /// The ParaView file of `step` at `time` (s), if the output interval says so.
  void output_step(int step, double time) const;
  /// What a restart after this step needs, and back (`file` names the source in errors).
  RestartData restart_data() const;
  void restore(const RestartData& data, const std::filesystem::path& file);

  int step() const { return step_; }
  int cells() const { return parameters_.geometry.cells; }
  const TubeRingmodelParameters& parameters() const { return parameters_; }
  Eigen::VectorXd cell_centres() const { return parameters_.geometry.cell_centres(); }
  const Eigen::VectorXd& displacement() const { return displacement_; }

  /// The tube law for one ring: pressure (Pa) -> radial displacement.
  double displacement_at(double pressure) const;

 private:
  TubeRingmodelParameters parameters_;
  int step_;
  double c02_;  ///< c0^2 = cmk2 - p_ref / (2 rho_f)
  Eigen::VectorXd pressure_;
  Eigen::VectorXd displacement_;
  bool converged_at_first_iteration_ = false;
};

}  // namespace cocopp::tube
