#pragma once
// What the three tube solvers share when reading their own YAML input files: the geometry and
// output keys, and pi. The files themselves are read with cocopp::Settings
// (core/case/settings.hpp): every read records its key, Settings::check_unused_keys() then
// reports keys nobody asked for, and all errors are cocopp::CaseError
// "file:line:col: 'key.path': message".
#include <Eigen/Dense>
#include <string>

#include "core/case/settings.hpp"

namespace cocopp::tube {

constexpr double kPi = 3.14159265358979323846;

/// Geometry shared by the three tube solvers (keys `length`, `diameter`, `cells`).
struct TubeGeometry {
  double length = 0.0;
  double diameter = 0.0;
  int cells = 0;

  double radius() const { return 0.5 * diameter; }
  double cell_size() const { return length / cells; }
  /// Cross-section at rest, pi d^2 / 4.
  double area() const;
  /// Cell centres z_i = -l/2 + dz/2 + i dz, i = 0..m-1 (the tube is centred on z = 0).
  Eigen::VectorXd cell_centres() const;

  static TubeGeometry read(const Settings& input);
};

/// `output: {interval: N, directory: dir}`; interval 0 writes nothing.
struct OutputSettings {
  int interval = 0;
  std::string directory = "output";

  bool due(int step) const { return interval > 0 && step % interval == 0; }
  static OutputSettings read(const Settings& input);
};

/// `residual_atol` of a wall model's input file (m, > 0), which only solver-coupling
/// convergence reads: below it a solve counts as converged at its first iteration. 0 when the
/// file does not give it.
double read_residual_atol(const Settings& input);
/// Throws std::runtime_error naming `model`'s input file and what the tolerance bounds
/// (`measure`, e.g. "residual of the wall equation") unless residual_atol was given.
void require_residual_atol(double residual_atol, const std::string& model,
                           const std::string& measure);

/// Read a solver's input file with `Parameters::read`; keys nobody read are errors.
template <class Parameters>
Parameters load_input_file(const std::string& file) {
  const Settings input = Settings::load_file(file);
  Parameters parameters = Parameters::read(input);
  input.check_unused_keys();
  return parameters;
}

/// Moens-Korteweg wave speed squared in kinematic units, E h / (rho_f d): flow and ring model.
inline double moens_korteweg_speed_squared(double e, double h, double rho_f, double diameter) {
  return e * h / (rho_f * diameter);
}

}  // namespace cocopp::tube
