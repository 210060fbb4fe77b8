#pragma once
// TubeFlow: incompressible, inviscid flow in a 1D tube with a radially deforming wall
// (docs/tube-solvers.md). Unknowns X = [u_0, p_0, u_1, p_1, ..., u_{m+1}, p_{m+1}]: the m cells
// plus one boundary value at each end; p is kinematic (p / rho_f). One coupling iteration takes
// the radial wall displacement of the m cells and returns their pressure in Pa.
#include <Eigen/Dense>
#include <string>

#include "core/data/restart_file.hpp"
#include "solvers/tube/banded_solver.hpp"
#include "solvers/tube/tube_input.hpp"

namespace cocopp::tube {

enum class InletBoundary { kPressure, kVelocity, kTotalPressure };
enum class InletFunction { kSine, kPulse, kSin2, kConstant, kRamp };
enum class OutletBoundary { kFixed, kNonReflecting };

/// The prescribed inlet value: reference + a function of the time step (pressures in Pa,
/// velocities in m/s).
struct InletParameters {
  InletBoundary boundary = InletBoundary::kPressure;
  InletFunction variable = InletFunction::kConstant;
  double reference = 0.0;
  double amplitude = 0.0;
  double period = 0.0;  ///< unused by `constant`

  /// Value at time step `step` (1-based, t = step * delta_t).
  double value(int step, double delta_t) const;
};

struct OutletParameters {
  OutletBoundary boundary = OutletBoundary::kFixed;
  double pressure = 0.0;  ///< Pa, fixed outlet only
};

struct TubeFlowParameters {
  TubeGeometry geometry;
  double rho_f = 0.0;  ///< kg/m^3
  double e = 0.0;      ///< Young's modulus of the wall, Pa
  double h = 0.0;      ///< wall thickness, m
  double u_ref = 0.0;  ///< reference velocity of the pressure stabilisation, m/s
  double u0 = 0.0;     ///< initial velocity, m/s
  double p_ref = 0.0;  ///< initial pressure, Pa
  InletParameters inlet;
  OutletParameters outlet;
  int newtonmax = 0;
  double newtontol = 0.0;
  OutputSettings output;

  /// Moens-Korteweg wave speed squared, E h / (rho_f d), in m^2/s^2.
  double wave_speed_squared() const;

  /// Read the keys of a flow input file (unknown keys are reported by the caller's
  /// input.check_unused_keys()).
  static TubeFlowParameters read(const Settings& input);
  /// Read a flow input file and reject unknown keys.
  static TubeFlowParameters load(const std::string& file);
};

class TubeFlow {
 public:
  /// The state at the end of time step `timestep_start`: u = u0, p = p_ref, undeformed wall.
  TubeFlow(TubeFlowParameters parameters, double delta_t, int timestep_start = 0);

  /// Start the next time step: saves the old values and evaluates the inlet value.
  void initialize_step();
  /// One coupling iteration: radial displacements of the m cells -> their pressures in Pa.
  Eigen::VectorXd solve(const Eigen::VectorXd& displacement);
  void finalize_step();
  /// Write the ParaView file of `step` if the output interval says so.
  /// The ParaView file of `step` at `time` (s), if the output interval says so.
  void output_step(int step, double time) const;
  /// What a restart after this step needs, and back (`file` names the source in errors).
  RestartData restart_data() const;
  void restore(const RestartData& data, const std::filesystem::path& file);

  int step() const { return step_; }
  double delta_t() const { return delta_t_; }
  const TubeFlowParameters& parameters() const { return parameters_; }
  int cells() const { return cells_; }
  Eigen::VectorXd cell_centres() const { return parameters_.geometry.cell_centres(); }
  /// Velocity u_1..u_m in m/s.
  Eigen::VectorXd velocity() const;
  /// Pressure rho_f p_1..rho_f p_m in Pa.
  Eigen::VectorXd pressure() const;
  /// Cross-sections a_1..a_m.
  Eigen::VectorXd areas() const { return areas_.segment(1, cells_); }
  Eigen::VectorXd displacement() const { return displacement_; }
  /// Newton steps made in the last solve.
  int newton_iterations() const { return newton_iterations_; }
  /// ||f|| / f0 after the last solve.
  double relative_residual() const { return relative_residual_; }
  /// Solver-coupling convergence: the last solve needed no Newton step, because the previous
  /// iterate already met newtontol for the new displacement (never at a step's first solve).
  bool converged_at_first_iteration() const { return converged_at_first_iteration_; }
  /// Newton always starts from the previous iterate: nothing to check.
  void start_reporting_convergence() const {}

  // The discrete system at the current areas, old values and inlet value, exposed so that
  // tests can check the Jacobian against finite differences.
  const Eigen::VectorXd& unknowns() const { return unknowns_; }
  Eigen::VectorXd residual(const Eigen::VectorXd& unknowns) const;
  BandedMatrix jacobian(const Eigen::VectorXd& unknowns) const;
  /// Set the areas from the displacement of the m cells (done by solve()).
  void set_displacement(const Eigen::VectorXd& displacement);

 private:
  void update_inlet_value();
  void impose_inlet_value(Eigen::VectorXd& unknowns) const;
  double total_pressure_head(const Eigen::VectorXd& unknowns) const;
  double characteristic_root() const;
  /// Neighbour velocities, face areas and upwind values of cell i, shared by the residual
  /// rows and their Jacobian.
  struct CellStencil {
    double u_left, u_centre, u_right, area_left, area_right, s, upwind_left, upwind_right;
  };
  CellStencil cell_stencil(const Eigen::VectorXd& x, int i) const;
  void add_cell_rows(const Eigen::VectorXd& x, Eigen::VectorXd& f) const;
  void add_cell_jacobian(const Eigen::VectorXd& x, BandedMatrix& jacobian) const;

  TubeFlowParameters parameters_;
  double delta_t_;
  int step_;
  int cells_;
  double dz_;
  double alpha_;                  ///< pressure stabilisation, (pi d^2 / 4) / (u_ref + dz / dt)
  double wave_speed2_;            ///< cmk2
  double inlet_value_;            ///< this step's inlet value, kinematic for pressures
  Eigen::VectorXd unknowns_;      ///< X, 2m + 4 values
  Eigen::VectorXd old_unknowns_;  ///< X at the start of the time step
  Eigen::VectorXd areas_;         ///< a_0..a_{m+1}
  Eigen::VectorXd old_areas_;
  Eigen::VectorXd displacement_;
  bool first_iteration_ = true;
  double initial_residual_ = 0.0;  ///< f0 of the current time step
  int newton_iterations_ = 0;
  double relative_residual_ = 0.0;
  bool converged_at_first_iteration_ = false;
};

}  // namespace cocopp::tube
