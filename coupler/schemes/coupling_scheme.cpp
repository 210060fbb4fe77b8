#include "coupler/schemes/coupling_scheme.hpp"

#include <fmt/format.h>

#include "coupler/results/run_outcome.hpp"
#include "solver_wrappers/solver_error.hpp"

namespace cocopp {

CouplingScheme::CouplingScheme(Parts parts)
    : solvers_{parts.first, parts.second},
      interpolation_(parts.interpolation),
      time_average_(parts.time_average),
      backtracking_(parts.backtracking),
      divergence_advice_(std::move(parts.divergence_advice)) {}

void CouplingScheme::start() {
  // Both processes start side by side: each takes milliseconds to load and read its input.
  for (int i = 0; i < 2; ++i) timed(i, [&] { solvers_[i]->start(); });
  for (int i = 0; i < 2; ++i) timed(i, [&] { solvers_[i]->initialize(); });
  for (auto* solver : solvers_) solver->overlap_step_requests();
  adopt_interfaces();
  check_interfaces_match();
  x_ = solvers_[0]->input_interface();
  y_ = solvers_[0]->output_interface();
  // Start from the displacement the second solver reports for its initial state (and the
  // loads the first reports for its own).
  x_.set_data(solvers_[1]->output_interface().data());
  on_started();
}

void CouplingScheme::adopt_interfaces() {
  if (solvers_[0]->adopts_interfaces() && solvers_[1]->adopts_interfaces())
    throw std::runtime_error(fmt::format(
        "solvers '{}' and '{}' are both mapped: one of them must keep its own interface, which "
        "the other maps onto",
        solvers_[0]->name(), solvers_[1]->name()));
  for (int i = 0; i < 2; ++i) {
    SolverWrapper& other = *solvers_[1 - i];
    if (solvers_[i]->adopts_interfaces())
      timed(i, [&] {
        solvers_[i]->adopt_interfaces(other.output_interface(), other.input_interface());
      });
  }
}

void CouplingScheme::check_interfaces_match() const {
  const SolverWrapper& first = *solvers_[0];
  const SolverWrapper& second = *solvers_[1];
  auto mismatch = [](const SolverWrapper& from, const Interface& out, const SolverWrapper& to,
                     const Interface& in) {
    return std::runtime_error(fmt::format(
        "the interfaces of the solvers do not fit together: '{}' gives [{}] but '{}' takes "
        "[{}]. Both sides need the same model parts, point counts and variables in the same "
        "order (non-matching meshes need a mapper)",
        from.name(), out.describe(), to.name(), in.describe()));
  };
  if (!first.output_interface().same_layout(second.input_interface()))
    throw mismatch(first, first.output_interface(), second, second.input_interface());
  if (!second.output_interface().same_layout(first.input_interface()))
    throw mismatch(second, second.output_interface(), first, first.input_interface());
}

const Interface& CouplingScheme::timed_solve(int index, const Interface& input) {
  const Interface* output = nullptr;
  timed(index, [&] { output = &solvers_[index]->solve(input); });
  return *output;
}

void CouplingScheme::begin_step(int step, double time) {
  step_ = step;
  step_times_ = {0.0, 0.0};
  step_overlap_ = 0.0;
  for (int i = 0; i < 2; ++i) timed(i, [&] { solvers_[i]->initialize_step(step, time); });
  on_step_begun();
}

Eigen::VectorXd CouplingScheme::evaluate_stepping_back(Eigen::VectorXd& u,
                                                       const Eigen::VectorXd& accepted,
                                                       int iteration,
                                                       std::vector<std::string>& notes) {
  std::string first_rejection;  // the one that says what went wrong with the iteration's input
  for (int retry = 1;; ++retry) {
    try {
      return evaluate(u, iteration);
    } catch (const SolverRejectedInput& e) {
      if (first_rejection.empty()) first_rejection = e.what();
      if (retry > backtracking_.retries)
        throw SolverError(
            e.solver_name(),
            fmt::format("{}\n(time step {}, coupling iteration {}: the coupled solver stepped "
                        "back {} times towards the last input both solvers accepted, "
                        "coupled_solver.backtracking.retries = {})",
                        first_rejection, step_, iteration, backtracking_.retries,
                        backtracking_.retries));
      // The rejected input lies too far from one the solver can take: the step towards it
      // from the last accepted input is too long, whatever made it (a quasi-Newton update
      // from poor secant information, an extrapolating predictor).
      u = accepted + backtracking_.factor * (u - accepted);
      notes.push_back(fmt::format(
          "solver '{}' rejected the input of iteration {}: the step from the last accepted "
          "input was shortened {} time(s) by {:g}",
          e.solver_name(), iteration, retry, backtracking_.factor));
    }
  }
}

void CouplingScheme::commit_step() {
  for (int i = 0; i < 2; ++i) timed(i, [&] { solvers_[i]->finalize_step(); });
  for (int i = 0; i < 2; ++i) timed(i, [&] { solvers_[i]->output_step(); });
  // Both solvers commit and write side by side; a failure there still ends this step.
  for (int i = 0; i < 2; ++i) timed(i, [&] { solvers_[i]->complete_step_requests(); });
}

void CouplingScheme::save_restarts(int step) {
  for (int i = 0; i < 2; ++i) timed(i, [&] { solvers_[i]->save_restart(step); });
}

void CouplingScheme::check_finite(const Interface& data, const SolverWrapper& solver,
                                  int iteration) const {
  if (data.data().allFinite()) return;
  for (const auto& block : data.blocks()) {
    const auto values = data.values(block.model_part, block.variable);
    for (Eigen::Index point = 0; point < values.rows(); ++point)
      if (!values.row(point).allFinite())
        throw DivergenceError(DivergenceKind::kNonFinite, step_, iteration,
                              fmt::format("solver '{}' returned a non-finite {} at model part "
                                          "'{}', point {} (of {}), in time step {}, coupling "
                                          "iteration {}. {}",
                                          solver.name(), block.variable, block.model_part, point,
                                          values.rows(), step_, iteration, divergence_advice_));
  }
}

}  // namespace cocopp
