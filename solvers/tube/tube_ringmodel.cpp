#include "solvers/tube/tube_ringmodel.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "solvers/tube/tube_output.hpp"

namespace cocopp::tube {

double TubeRingmodelParameters::wave_speed_squared() const {
  return moens_korteweg_speed_squared(e, h, rho_f, geometry.diameter);
}

TubeRingmodelParameters TubeRingmodelParameters::read(const Settings& input) {
  TubeRingmodelParameters parameters;
  parameters.geometry = TubeGeometry::read(input);
  parameters.rho_f = input.required_in_range("rho_f", Range::positive());
  parameters.e = input.required_in_range("e", Range::positive());
  parameters.h = input.required_in_range("h", Range::positive());
  parameters.p_ref = input.get<double>("p_ref", 0.0);
  parameters.residual_atol = read_residual_atol(input);
  parameters.output = OutputSettings::read(input);
  return parameters;
}

TubeRingmodelParameters TubeRingmodelParameters::load(const std::string& file) {
  const Settings input = Settings::load_file(file);
  TubeRingmodelParameters parameters = read(input);
  // c0^2 must be positive; report it against the input file.
  if (parameters.wave_speed_squared() - parameters.p_ref / (2.0 * parameters.rho_f) <= 0.0) {
    input.fail("p_ref", "too high: E h / (rho_f d) - p_ref / (2 rho_f) must be positive");
  }
  input.check_unused_keys();
  return parameters;
}

TubeRingmodel::TubeRingmodel(TubeRingmodelParameters parameters, int timestep_start)
    : parameters_(std::move(parameters)),
      step_(timestep_start),
      c02_(parameters_.wave_speed_squared() - parameters_.p_ref / (2.0 * parameters_.rho_f)) {
  if (!(c02_ > 0.0)) {
    throw std::invalid_argument(
        "TubeRingmodel: p_ref too high, c0^2 = cmk2 - p_ref/(2 rho_f) <= 0");
  }
  pressure_ = Eigen::VectorXd::Constant(cells(), parameters_.p_ref);
  displacement_ = Eigen::VectorXd::Zero(cells());
}

double TubeRingmodel::displacement_at(double pressure) const {
  const double rho_f = parameters_.rho_f;
  const double p_kinematic = pressure / rho_f;
  const double p_ref_kinematic = parameters_.p_ref / rho_f;
  // The spec's limit is p_k > 2 c0^2 + p_ref / rho_f; at equality the area is infinite too.
  if (p_kinematic >= 2.0 * c02_ + p_ref_kinematic) {
    std::ostringstream message;
    message << "unphysical pressure " << pressure << " Pa in the tube ring model: the tube law "
            << "allows only p < " << rho_f * (2.0 * c02_ + p_ref_kinematic) << " Pa";
    throw std::runtime_error(message.str());
  }
  const double ratio = 2.0 / (2.0 + (p_ref_kinematic - p_kinematic) / c02_);
  const double area = parameters_.geometry.area() * ratio * ratio;
  return std::sqrt(area / kPi) - parameters_.geometry.radius();
}

Eigen::VectorXd TubeRingmodel::solve(const Eigen::VectorXd& pressure) {
  if (pressure.size() != cells()) {
    throw std::invalid_argument("TubeRingmodel: expected " + std::to_string(cells()) +
                                " pressures, got " + std::to_string(pressure.size()));
  }
  Eigen::VectorXd displacement(cells());
  for (int i = 0; i < cells(); ++i) displacement[i] = displacement_at(pressure[i]);
  converged_at_first_iteration_ = parameters_.residual_atol > 0.0 &&
                                  (displacement - displacement_).norm() < parameters_.residual_atol;
  pressure_ = pressure;
  displacement_ = displacement;
  return displacement_;
}

void TubeRingmodel::start_reporting_convergence() const {
  require_residual_atol(parameters_.residual_atol, "tube ring model", "change of the displacement");
}

RestartData TubeRingmodel::restart_data() const {
  return {{"pressure", pressure_}, {"displacement", displacement_}};
}

void TubeRingmodel::restore(const RestartData& data, const std::filesystem::path& file) {
  pressure_ = restart_array(data, "pressure", cells(), file);
  displacement_ = restart_array(data, "displacement", cells(), file);
}

void TubeRingmodel::output_step(int step, double time) const {
  write_output(
      parameters_.output, "tube_ringmodel", step, time, parameters_.geometry, displacement_,
      {{"displacement", radial_vectors(displacement_), true}, {"pressure", pressure_, false}});
}

}  // namespace cocopp::tube
