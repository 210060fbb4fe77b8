#include "solvers/tube/tube_structure.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "solvers/tube/tube_output.hpp"

namespace cocopp::tube {

namespace {

void read_time_scheme(const Settings& input, TubeStructureParameters& parameters) {
  const Settings scheme = input.child_or_empty("time_scheme");
  const std::string type =
      scheme.get_choice("type", "backward_euler", {"backward_euler", "newmark"});
  if (type == "backward_euler") {
    for (const char* key : {"beta", "gamma"}) {
      if (scheme.has(key)) scheme.fail(key, "only the newmark time scheme takes beta and gamma");
    }
    parameters.time_scheme = TimeScheme::kBackwardEuler;
    parameters.beta = 1.0;
    parameters.gamma = 1.0;
    return;
  }
  parameters.time_scheme = TimeScheme::kNewmark;
  // Defaults: the average-acceleration (trapezoidal) rule, unconditionally stable and
  // without numerical damping.
  parameters.gamma = scheme.get_in_range("gamma", 0.5, Range::at_least(0.5));
  parameters.beta = scheme.get_in_range("beta", 0.25, Range::positive());
  const double min_beta = (0.5 + parameters.gamma) * (0.5 + parameters.gamma) / 4.0;
  if (parameters.beta < min_beta) {
    scheme.fail("beta", "must be >= (1/2 + gamma)^2 / 4 = " + std::to_string(min_beta) +
                            " for unconditional stability");
  }
}

}  // namespace

TubeStructureParameters TubeStructureParameters::read(const Settings& input) {
  TubeStructureParameters parameters;
  parameters.geometry = TubeGeometry::read(input);
  parameters.rho_s = input.required_in_range("rho_s", Range::positive());
  parameters.e = input.required_in_range("e", Range::positive());
  parameters.h = input.required_in_range("h", Range::positive());
  parameters.nu = input.required_in_range("nu", Range{0.0, 0.5, false, true});
  parameters.p_ref = input.get<double>("p_ref", 0.0);
  parameters.residual_atol = read_residual_atol(input);
  read_time_scheme(input, parameters);
  parameters.output = OutputSettings::read(input);
  return parameters;
}

TubeStructureParameters TubeStructureParameters::load(const std::string& file) {
  return load_input_file<TubeStructureParameters>(file);
}

TubeStructure::TubeStructure(TubeStructureParameters parameters, double delta_t, int timestep_start)
    : parameters_(std::move(parameters)),
      delta_t_(delta_t),
      step_(timestep_start),
      cells_(parameters_.geometry.cells),
      dz_(parameters_.geometry.cell_size()),
      r0_(parameters_.geometry.radius()) {
  if (!(delta_t > 0.0)) {
    throw std::invalid_argument("TubeStructure: the time step must be positive");
  }
  const double e = parameters_.e, h = parameters_.h, nu = parameters_.nu;
  b1_ = (h * e / (1.0 - nu * nu)) * h * h / 12.0;
  b2_ = b1_ * 2.0 * nu / (r0_ * r0_);
  b3_ = h * e / ((1.0 - nu * nu) * r0_ * r0_);
  const double dz2 = dz_ * dz_, dz4 = dz2 * dz2;
  const double mass = parameters_.rho_s * h;
  diagonal_ =
      mass / (parameters_.beta * delta_t * delta_t) + 6.0 * b1_ / dz4 + 2.0 * b2_ / dz2 + b3_;
  neighbour_ = -4.0 * b1_ / dz4 - b2_ / dz2;
  second_ = b1_ / dz4;
  matrix_ = assemble();
  lu_ = BandedLu(matrix_);

  radius_ = Eigen::VectorXd::Constant(cells_, r0_);
  old_radius_ = radius_;
  velocity_ = Eigen::VectorXd::Zero(cells_);
  old_velocity_ = velocity_;
  acceleration_ = Eigen::VectorXd::Zero(cells_);
  old_acceleration_ = acceleration_;
  pressure_ = Eigen::VectorXd::Constant(cells_, parameters_.p_ref);
}

// The pentadiagonal matrix over the m cells, rows divided by C for conditioning; the clamped
// ends' ghost values (r0) enter the right-hand side instead.
BandedMatrix TubeStructure::assemble() const {
  BandedMatrix matrix(cells_, 2, 2);
  for (int i = 0; i < cells_; ++i) {
    matrix(i, i) = 1.0;
    for (int offset : {-1, 1}) {
      if (i + offset >= 0 && i + offset < cells_) matrix(i, i + offset) = neighbour_ / diagonal_;
    }
    for (int offset : {-2, 2}) {
      if (i + offset >= 0 && i + offset < cells_) matrix(i, i + offset) = second_ / diagonal_;
    }
  }
  return matrix;
}

double TubeStructure::newmark_switch() const {
  return parameters_.time_scheme == TimeScheme::kNewmark ? 1.0 : 0.0;
}

void TubeStructure::initialize_step() {
  ++step_;
  old_radius_ = radius_;
  old_velocity_ = velocity_;
  old_acceleration_ = acceleration_;
}

Eigen::VectorXd TubeStructure::solve(const Eigen::VectorXd& pressure) {
  if (pressure.size() != cells_) {
    throw std::invalid_argument("TubeStructure: expected " + std::to_string(cells_) +
                                " pressures, got " + std::to_string(pressure.size()));
  }
  pressure_ = pressure;
  const double beta = parameters_.beta;
  const double mass = parameters_.rho_s * parameters_.h;
  const double dt = delta_t_;
  const double n = newmark_switch();
  Eigen::VectorXd rhs(cells_);
  for (int i = 0; i < cells_; ++i) {
    double value = b3_ * r0_ + (pressure[i] - parameters_.p_ref) +
                   mass * (old_radius_[i] / (beta * dt * dt) + old_velocity_[i] / (beta * dt) +
                           old_acceleration_[i] * (1.0 / (2.0 * beta) - 1.0) * n);
    // Ghost values outside the tube are held at r0 (clamped ends).
    for (int offset : {-1, 1}) {
      if (i + offset < 0 || i + offset >= cells_) value -= neighbour_ * r0_;
    }
    for (int offset : {-2, 2}) {
      if (i + offset < 0 || i + offset >= cells_) value -= second_ * r0_;
    }
    rhs[i] = value / diagonal_;
  }
  converged_at_first_iteration_ =
      parameters_.residual_atol > 0.0 &&
      (matrix_.multiply(radius_) - rhs).norm() < parameters_.residual_atol;
  radius_ = lu_.solve(rhs);
  return displacement();
}

void TubeStructure::start_reporting_convergence() const {
  require_residual_atol(parameters_.residual_atol, "tube structure",
                        "residual of the wall equation");
}

void TubeStructure::finalize_step() {
  const double beta = parameters_.beta, gamma = parameters_.gamma, dt = delta_t_;
  const double n = newmark_switch();
  acceleration_ = (radius_ - old_radius_) / (beta * dt * dt) - old_velocity_ / (beta * dt) -
                  old_acceleration_ * ((1.0 / (2.0 * beta) - 1.0) * n);
  velocity_ = old_velocity_ + dt * (1.0 - gamma) * old_acceleration_ + dt * gamma * acceleration_;
}

RestartData TubeStructure::restart_data() const {
  return {{"radius", radius_},
          {"velocity", velocity_},
          {"acceleration", acceleration_},
          {"pressure", pressure_}};
}

void TubeStructure::restore(const RestartData& data, const std::filesystem::path& file) {
  radius_ = old_radius_ = restart_array(data, "radius", cells_, file);
  velocity_ = old_velocity_ = restart_array(data, "velocity", cells_, file);
  acceleration_ = old_acceleration_ = restart_array(data, "acceleration", cells_, file);
  pressure_ = restart_array(data, "pressure", cells_, file);
}

Eigen::VectorXd TubeStructure::displacement() const {
  return (radius_.array() - r0_).matrix();
}

void TubeStructure::output_step(int step, double time) const {
  const Eigen::VectorXd dr = displacement();
  write_output(parameters_.output, "tube_structure", step, time, parameters_.geometry, dr,
               {{"displacement", radial_vectors(dr), true}, {"pressure", pressure_, false}});
}

}  // namespace cocopp::tube
