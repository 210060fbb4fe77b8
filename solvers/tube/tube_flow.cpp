#include "solvers/tube/tube_flow.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "solvers/tube/tube_output.hpp"

namespace cocopp::tube {

namespace {

// Positions of u_i and p_i in the interleaved unknowns.
constexpr int velocity_index(int i) {
  return 2 * i;
}
constexpr int pressure_index(int i) {
  return 2 * i + 1;
}

// Four sub- and four super-diagonals: the boundary rows extrapolate over two cells.
constexpr int kBandwidth = 4;

InletBoundary read_inlet_boundary(const Settings& inlet) {
  const std::string name =
      inlet.required_choice("boundary", {"pressure", "velocity", "total_pressure"});
  if (name == "velocity") return InletBoundary::kVelocity;
  if (name == "total_pressure") return InletBoundary::kTotalPressure;
  return InletBoundary::kPressure;
}

InletFunction read_inlet_function(const Settings& inlet) {
  const std::string name =
      inlet.required_choice("variable", {"sine", "pulse", "sin2", "constant", "ramp"});
  if (name == "sine") return InletFunction::kSine;
  if (name == "pulse") return InletFunction::kPulse;
  if (name == "sin2") return InletFunction::kSin2;
  if (name == "ramp") return InletFunction::kRamp;
  return InletFunction::kConstant;
}

InletParameters read_inlet(const Settings& input) {
  const Settings section = input.child("inlet");
  InletParameters inlet;
  inlet.boundary = read_inlet_boundary(section);
  inlet.variable = read_inlet_function(section);
  inlet.reference = section.get<double>("reference", 0.0);
  inlet.amplitude = section.required<double>("amplitude");
  // A constant inlet has no period; it is accepted (and ignored) so that switching the
  // function does not require deleting the key.
  inlet.period = inlet.variable == InletFunction::kConstant
                     ? section.get<double>("period", 0.0)
                     : section.required_in_range("period", Range::positive());
  return inlet;
}

OutletParameters read_outlet(const Settings& input) {
  const Settings section = input.child("outlet");
  OutletParameters outlet;
  const std::string name = section.required_choice("boundary", {"fixed", "non_reflecting"});
  outlet.boundary = name == "fixed" ? OutletBoundary::kFixed : OutletBoundary::kNonReflecting;
  if (outlet.boundary == OutletBoundary::kFixed) {
    outlet.pressure = section.get<double>("pressure", 0.0);
  } else if (section.has("pressure")) {
    section.fail("pressure", "a non_reflecting outlet takes no pressure");
  }
  return outlet;
}

}  // namespace

double InletParameters::value(int step, double delta_t) const {
  const double t = step * delta_t;
  switch (variable) {
    case InletFunction::kSine:
      return reference + amplitude * std::sin(2.0 * kPi * t / period);
    case InletFunction::kPulse: {
      // n <= T / dt, with a relative tolerance so that 0.003 / 1e-4 = 29.999... keeps step 30.
      const bool on = step <= period / delta_t * (1.0 + 1e-12);
      return reference + (on ? amplitude : 0.0);
    }
    case InletFunction::kSin2: {
      const double sine = std::sin(kPi * t / period);
      return reference + amplitude * sine * sine;
    }
    case InletFunction::kRamp:
      return reference + amplitude * t / period;
    case InletFunction::kConstant:
      break;
  }
  return reference + amplitude;
}

double TubeFlowParameters::wave_speed_squared() const {
  return moens_korteweg_speed_squared(e, h, rho_f, geometry.diameter);
}

TubeFlowParameters TubeFlowParameters::read(const Settings& input) {
  TubeFlowParameters parameters;
  parameters.geometry = TubeGeometry::read(input);
  parameters.rho_f = input.required_in_range("rho_f", Range::positive());
  parameters.e = input.required_in_range("e", Range::positive());
  parameters.h = input.required_in_range("h", Range::positive());
  parameters.u_ref = input.required_in_range("u_ref", Range::non_negative());
  parameters.u0 = input.get<double>("u0", 0.0);
  parameters.p_ref = input.get<double>("p_ref", 0.0);
  parameters.inlet = read_inlet(input);
  parameters.outlet = read_outlet(input);
  parameters.newtonmax = input.required_int_in_range("newtonmax", 1);
  parameters.newtontol = input.required_in_range("newtontol", Range::positive());
  parameters.output = OutputSettings::read(input);
  return parameters;
}

TubeFlowParameters TubeFlowParameters::load(const std::string& file) {
  return load_input_file<TubeFlowParameters>(file);
}

TubeFlow::TubeFlow(TubeFlowParameters parameters, double delta_t, int timestep_start)
    : parameters_(std::move(parameters)),
      delta_t_(delta_t),
      step_(timestep_start),
      cells_(parameters_.geometry.cells),
      dz_(parameters_.geometry.cell_size()),
      alpha_(parameters_.geometry.area() / (parameters_.u_ref + dz_ / delta_t)),
      wave_speed2_(parameters_.wave_speed_squared()) {
  if (!(delta_t > 0.0)) throw std::invalid_argument("TubeFlow: the time step must be positive");
  if (cells_ < 2) throw std::invalid_argument("TubeFlow: at least two cells are needed");
  const int size = 2 * cells_ + 4;
  unknowns_.resize(size);
  for (int i = 0; i <= cells_ + 1; ++i) {
    unknowns_[velocity_index(i)] = parameters_.u0;
    unknowns_[pressure_index(i)] = parameters_.p_ref / parameters_.rho_f;
  }
  old_unknowns_ = unknowns_;
  areas_ = Eigen::VectorXd::Constant(cells_ + 2, parameters_.geometry.area());
  old_areas_ = areas_;
  displacement_ = Eigen::VectorXd::Zero(cells_);
  update_inlet_value();
}

void TubeFlow::initialize_step() {
  ++step_;
  old_unknowns_ = unknowns_;
  old_areas_ = areas_;
  update_inlet_value();
  first_iteration_ = true;
}

void TubeFlow::update_inlet_value() {
  const double value = parameters_.inlet.value(step_, delta_t_);
  inlet_value_ =
      parameters_.inlet.boundary == InletBoundary::kVelocity ? value : value / parameters_.rho_f;
}

RestartData TubeFlow::restart_data() const {
  return {{"unknowns", unknowns_}, {"areas", areas_}, {"displacement", displacement_}};
}

void TubeFlow::restore(const RestartData& data, const std::filesystem::path& file) {
  unknowns_ = restart_array(data, "unknowns", unknowns_.size(), file);
  areas_ = restart_array(data, "areas", areas_.size(), file);
  displacement_ = restart_array(data, "displacement", displacement_.size(), file);
  old_unknowns_ = unknowns_;
  old_areas_ = areas_;
}

void TubeFlow::finalize_step() {
  first_iteration_ = true;
}

void TubeFlow::set_displacement(const Eigen::VectorXd& displacement) {
  if (displacement.size() != cells_) {
    throw std::invalid_argument("TubeFlow: expected " + std::to_string(cells_) +
                                " displacements, got " + std::to_string(displacement.size()));
  }
  displacement_ = displacement;
  const double d = parameters_.geometry.diameter;
  for (int i = 1; i <= cells_; ++i) {
    const double diameter = d + 2.0 * displacement[i - 1];
    areas_[i] = kPi * diameter * diameter / 4.0;
  }
  areas_[0] = areas_[1];
  areas_[cells_ + 1] = areas_[cells_];
}

Eigen::VectorXd TubeFlow::solve(const Eigen::VectorXd& displacement) {
  set_displacement(displacement);
  Eigen::VectorXd f = residual(unknowns_);
  double norm = f.norm();
  // As CoCoNuT's tube flow: the previous iterate, judged against the step's f0.
  converged_at_first_iteration_ =
      !first_iteration_ &&
      (initial_residual_ == 0.0 ? norm == 0.0 : norm / initial_residual_ < parameters_.newtontol);
  // f0 is taken at the first coupling iteration and kept for the whole time step, so later
  // iterations converge to the same absolute level. If the system was exactly solved at the
  // first iteration (f0 = 0), the first nonzero residual of the step takes its place.
  if (first_iteration_ || initial_residual_ == 0.0) initial_residual_ = norm;
  first_iteration_ = false;
  newton_iterations_ = 0;
  relative_residual_ = 0.0;
  if (initial_residual_ != 0.0) {
    for (int s = 0; s < parameters_.newtonmax; ++s) {
      unknowns_ -= solve_banded(jacobian(unknowns_), f);
      impose_inlet_value(unknowns_);
      f = residual(unknowns_);
      norm = f.norm();
      ++newton_iterations_;
      if (norm / initial_residual_ < parameters_.newtontol) break;
    }
    relative_residual_ = norm / initial_residual_;
  }
  return pressure();
}

void TubeFlow::impose_inlet_value(Eigen::VectorXd& x) const {
  switch (parameters_.inlet.boundary) {
    case InletBoundary::kPressure:
      x[pressure_index(0)] = inlet_value_;
      break;
    case InletBoundary::kVelocity:
      x[velocity_index(0)] = inlet_value_;
      break;
    case InletBoundary::kTotalPressure:
      x[velocity_index(0)] = std::sqrt(total_pressure_head(x));
      break;
  }
}

// 2 (P_in / rho_f - p_0) = u_0^2 for a total-pressure inlet.
double TubeFlow::total_pressure_head(const Eigen::VectorXd& x) const {
  const double head = 2.0 * (inlet_value_ - x[pressure_index(0)]);
  if (head < 0.0) {
    const double rho_f = parameters_.rho_f;
    throw std::runtime_error(
        "tube flow: in step " + std::to_string(step_) + " the inlet pressure " +
        std::to_string(rho_f * x[pressure_index(0)]) +
        " Pa exceeds the prescribed total pressure " + std::to_string(rho_f * inlet_value_) +
        " Pa, which a total_pressure inlet cannot represent (reverse flow). Start from a state "
        "close to the total pressure (p_ref + rho_f u0^2 / 2) or use smaller time steps.");
  }
  return head;
}

// sqrt(cmk2 - p_{m+1}^n / 2) of the non-reflecting outlet (constant within a time step).
double TubeFlow::characteristic_root() const {
  const double radicand = wave_speed2_ - old_unknowns_[pressure_index(cells_ + 1)] / 2.0;
  if (radicand < 0.0) {
    throw std::runtime_error("tube flow: outlet pressure too high for the non_reflecting outlet");
  }
  return std::sqrt(radicand);
}

Eigen::VectorXd TubeFlow::residual(const Eigen::VectorXd& x) const {
  const int m = cells_;
  Eigen::VectorXd f(2 * m + 4);
  auto u = [&x](int i) { return x[velocity_index(i)]; };
  auto p = [&x](int i) { return x[pressure_index(i)]; };

  switch (parameters_.inlet.boundary) {
    case InletBoundary::kPressure:
      f[0] = alpha_ * (u(0) - (2.0 * u(1) - u(2)));
      f[1] = alpha_ * (p(0) - inlet_value_);
      break;
    case InletBoundary::kVelocity:
      f[0] = alpha_ * (u(0) - inlet_value_);
      f[1] = alpha_ * (p(0) - (2.0 * p(1) - p(2)));
      break;
    case InletBoundary::kTotalPressure:
      f[0] = alpha_ * (u(0) - std::sqrt(total_pressure_head(x)));
      f[1] = alpha_ * (p(0) - (2.0 * p(1) - p(2)));
      break;
  }

  add_cell_rows(x, f);

  f[2 * m + 2] = alpha_ * (u(m + 1) - (2.0 * u(m) - u(m - 1)));
  if (parameters_.outlet.boundary == OutletBoundary::kFixed) {
    f[2 * m + 3] = alpha_ * (p(m + 1) - parameters_.outlet.pressure / parameters_.rho_f);
  } else {
    const double du = u(m + 1) - old_unknowns_[velocity_index(m + 1)];
    const double w = characteristic_root() - du / 4.0;
    f[2 * m + 3] = alpha_ * (p(m + 1) - 2.0 * (wave_speed2_ - w * w));
  }
  return f;
}

TubeFlow::CellStencil TubeFlow::cell_stencil(const Eigen::VectorXd& x, int i) const {
  CellStencil c;
  c.u_left = x[velocity_index(i - 1)];
  c.u_centre = x[velocity_index(i)];
  c.u_right = x[velocity_index(i + 1)];
  c.area_left = areas_[i] + areas_[i - 1];
  c.area_right = areas_[i] + areas_[i + 1];
  // Upwind velocities of the momentum fluxes.
  c.s = c.u_centre > 0.0 ? 1.0 : 0.0;
  c.upwind_left = c.s * c.u_left + (1.0 - c.s) * c.u_centre;
  c.upwind_right = c.s * c.u_centre + (1.0 - c.s) * c.u_right;
  return c;
}

void TubeFlow::add_cell_rows(const Eigen::VectorXd& x, Eigen::VectorXd& f) const {
  const Eigen::VectorXd& a = areas_;
  const Eigen::VectorXd& a_old = old_areas_;
  const double inertia = dz_ / delta_t_;
  for (int i = 1; i <= cells_; ++i) {
    const CellStencil c = cell_stencil(x, i);
    const double p_left = x[pressure_index(i - 1)];
    const double p_centre = x[pressure_index(i)];
    const double p_right = x[pressure_index(i + 1)];

    f[2 * i] = inertia * (a[i] - a_old[i]) + (c.u_centre + c.u_right) * c.area_right / 4.0 -
               (c.u_centre + c.u_left) * c.area_left / 4.0 -
               alpha_ * (p_right - 2.0 * p_centre + p_left);
    f[2 * i + 1] = inertia * (c.u_centre * a[i] - old_unknowns_[velocity_index(i)] * a_old[i]) +
                   c.upwind_right * (c.u_centre + c.u_right) * c.area_right / 4.0 -
                   c.upwind_left * (c.u_centre + c.u_left) * c.area_left / 4.0 +
                   ((p_right - p_centre) * c.area_right + (p_centre - p_left) * c.area_left) / 4.0;
  }
}

BandedMatrix TubeFlow::jacobian(const Eigen::VectorXd& x) const {
  const int m = cells_;
  BandedMatrix j(2 * m + 4, kBandwidth, kBandwidth);
  const int u0 = velocity_index(0), p0 = pressure_index(0);

  switch (parameters_.inlet.boundary) {
    case InletBoundary::kPressure:
      j(0, u0) = alpha_;
      j(0, velocity_index(1)) = -2.0 * alpha_;
      j(0, velocity_index(2)) = alpha_;
      j(1, p0) = alpha_;
      break;
    case InletBoundary::kTotalPressure: {
      const double head = total_pressure_head(x);
      if (head == 0.0) {
        throw std::runtime_error(
            "tube flow: inlet pressure equals the total pressure, the inlet velocity relation "
            "has no derivative there");
      }
      j(0, u0) = alpha_;
      j(0, p0) = alpha_ / std::sqrt(head);
      j(1, p0) = alpha_;
      j(1, pressure_index(1)) = -2.0 * alpha_;
      j(1, pressure_index(2)) = alpha_;
      break;
    }
    case InletBoundary::kVelocity:
      j(0, u0) = alpha_;
      j(1, p0) = alpha_;
      j(1, pressure_index(1)) = -2.0 * alpha_;
      j(1, pressure_index(2)) = alpha_;
      break;
  }

  add_cell_jacobian(x, j);

  const int row_u = 2 * m + 2, row_p = 2 * m + 3;
  j(row_u, velocity_index(m + 1)) = alpha_;
  j(row_u, velocity_index(m)) = -2.0 * alpha_;
  j(row_u, velocity_index(m - 1)) = alpha_;
  j(row_p, pressure_index(m + 1)) = alpha_;
  if (parameters_.outlet.boundary == OutletBoundary::kNonReflecting) {
    const double du = x[velocity_index(m + 1)] - old_unknowns_[velocity_index(m + 1)];
    // d/du of -2 (cmk2 - (S - du/4)^2) is -(S - du/4).
    j(row_p, velocity_index(m + 1)) = -alpha_ * (characteristic_root() - du / 4.0);
  }
  return j;
}

void TubeFlow::add_cell_jacobian(const Eigen::VectorXd& x, BandedMatrix& j) const {
  const Eigen::VectorXd& a = areas_;
  const double inertia = dz_ / delta_t_;
  for (int i = 1; i <= cells_; ++i) {
    const CellStencil c = cell_stencil(x, i);
    const double u_left = c.u_left, u_centre = c.u_centre, u_right = c.u_right;
    const double area_left = c.area_left, area_right = c.area_right, s = c.s;
    const double upwind_left = c.upwind_left, upwind_right = c.upwind_right;
    const int ul = velocity_index(i - 1), uc = velocity_index(i), ur = velocity_index(i + 1);
    const int pl = pressure_index(i - 1), pc = pressure_index(i), pr = pressure_index(i + 1);

    const int continuity = 2 * i;
    j(continuity, ul) = -area_left / 4.0;
    j(continuity, uc) = (area_right - area_left) / 4.0;
    j(continuity, ur) = area_right / 4.0;
    j(continuity, pl) = -alpha_;
    j(continuity, pc) = 2.0 * alpha_;
    j(continuity, pr) = -alpha_;

    // The upwind switch s is held fixed: the residual is piecewise smooth in u.
    const int momentum = 2 * i + 1;
    j(momentum, ul) = -area_left / 4.0 * (s * (u_centre + u_left) + upwind_left);
    j(momentum, uc) = inertia * a[i] +
                      area_right / 4.0 * (s * (u_centre + u_right) + upwind_right) -
                      area_left / 4.0 * ((1.0 - s) * (u_centre + u_left) + upwind_left);
    j(momentum, ur) = area_right / 4.0 * ((1.0 - s) * (u_centre + u_right) + upwind_right);
    j(momentum, pl) = -area_left / 4.0;
    j(momentum, pc) = (area_left - area_right) / 4.0;
    j(momentum, pr) = area_right / 4.0;
  }
}

Eigen::VectorXd TubeFlow::velocity() const {
  Eigen::VectorXd u(cells_);
  for (int i = 1; i <= cells_; ++i) u[i - 1] = unknowns_[velocity_index(i)];
  return u;
}

Eigen::VectorXd TubeFlow::pressure() const {
  Eigen::VectorXd p(cells_);
  for (int i = 1; i <= cells_; ++i) p[i - 1] = parameters_.rho_f * unknowns_[pressure_index(i)];
  return p;
}

void TubeFlow::output_step(int step, double time) const {
  write_output(parameters_.output, "tube_flow", step, time, parameters_.geometry, displacement_,
               {{"pressure", pressure(), false}, {"velocity", velocity(), false}});
}

}  // namespace cocopp::tube
