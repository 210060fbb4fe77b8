#include "coupler/coupled_solvers/coupled_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "solver_wrappers/solver_error.hpp"

namespace cocopp {

namespace {
using Clock = std::chrono::steady_clock;

/// Each distinct note once, in order of first appearance, with "(n times)" when repeated.
std::vector<std::string> count_repeats(const std::vector<std::string>& notes) {
  std::vector<std::pair<std::string, int>> counted;
  for (const auto& note : notes) {
    auto found = std::find_if(counted.begin(), counted.end(),
                              [&](const auto& entry) { return entry.first == note; });
    if (found == counted.end())
      counted.emplace_back(note, 1);
    else
      ++found->second;
  }
  std::vector<std::string> result;
  for (const auto& [note, count] : counted)
    result.push_back(count == 1 ? note : fmt::format("{} ({} times)", note, count));
  return result;
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}
}  // namespace

CoupledSolver::CoupledSolver(const Settings& settings)
    : type_(settings.required<std::string>("type")),
      predictor_type_(settings.child("predictor").required<std::string>("type")),
      predictor_(PredictorRegistry::instance().create(settings.child("predictor"))),
      criterion_(
          ConvergenceCriterionRegistry::instance().create(settings.child("convergence_criterion"))),
      divergence_factor_(
          settings.child_or_empty("divergence").get_in_range("factor", 1e6, Range::at_least(1.0))),
      growth_iterations_(
          settings.child_or_empty("divergence").get_int_in_range("growth_iterations", 10, 0)),
      backtracking_retries_(
          settings.child_or_empty("backtracking").get_int_in_range("retries", 4, 0)),
      backtracking_factor_(settings.child_or_empty("backtracking")
                               .get_in_range("factor", 0.5, {0.0, 1.0, true, true})) {}

void CoupledSolver::initialize(SolverWrapper& first, SolverWrapper& second) {
  solvers_ = {&first, &second};
  // Both processes start side by side: each takes milliseconds to load and read its input.
  for (int i = 0; i < 2; ++i) timed(i, [&] { solvers_[i]->start(); });
  for (int i = 0; i < 2; ++i) timed(i, [&] { solvers_[i]->initialize(); });
  for (auto* solver : solvers_) solver->overlap_step_requests();
  adopt_interfaces();
  check_interfaces_match();
  x_ = first.input_interface();
  y_ = first.output_interface();
  // Start from the displacement the second solver reports for its initial state.
  x_.set_data(second.output_interface().data());
  predictor_->initialize(x_.data());
  criterion_->attach_solvers(solvers_);
  on_initialized();
}

void CoupledSolver::adopt_interfaces() {
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

void CoupledSolver::check_interfaces_match() const {
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

template <class Call>
void CoupledSolver::timed(int index, Call call) {
  // Also a call that throws (a rejected input) took the solver's time, not the coupler's.
  const Stopwatch stopwatch(solver_time_step_[index], solver_time_total_[index]);
  call();
}

const Interface& CoupledSolver::timed_solve(int index, const Interface& input) {
  const Interface* output = nullptr;
  timed(index, [&] { output = &solvers_[index]->solve(input); });
  return *output;
}

StepRecord CoupledSolver::solve_step(int step, double time) {
  StepRecord record = iterate_step(step, time);
  commit_step(record);
  return record;
}

StepRecord CoupledSolver::iterate_step(int step, double time) {
  step_start_ = Clock::now();
  step_ = step;
  time_ = time;
  solver_time_step_ = {0.0, 0.0};
  own_solvers_time_step_ = 0.0;
  own_iterations_ = 0;
  StepRecord record;
  record.step = step;
  record.time = time;
  unfinished_step_ = step;
  unfinished_residuals_.clear();
  for (int i = 0; i < 2; ++i) timed(i, [&] { solvers_[i]->initialize_step(step, time); });

  // The previous step's converged input: what the solvers last accepted.
  Eigen::VectorXd accepted = x_.data();
  criterion_->initialize_step();
  on_step_start();
  Eigen::VectorXd x = first_input(predictor_->predict());
  bool tolerance_met = false;
  std::vector<std::string> notes;
  for (int iteration = 1;; ++iteration) {
    const Eigen::VectorXd xt = evaluate_stepping_back(x, accepted, step, iteration, notes);
    accepted = x;
    const Eigen::VectorXd r = xt - x;
    record.residual_norms.push_back(r.norm());
    unfinished_residuals_.push_back(record.residual_norms.back());
    record.iterations = iteration;
    if (iteration == 1) largest_first_residual_ = std::max(largest_first_residual_, r.norm());
    check_divergence(record.residual_norms, step, time, notes);
    if (!iterates()) {
      x = xt;  // explicit coupling accepts the structure's answer
      tolerance_met = true;
      break;
    }
    criterion_->update(convergence_residual(r));
    // The progress text is formatted for an observer, else once for the step's last iteration:
    // formatting it every iteration cost 7 % of the coupler's time on the tube.
    if (iteration_observer_)
      iteration_observer_({step, iteration, record.residual_norms.back(), criterion_->progress(),
                           seconds_since(step_start_), &r});
    if (criterion_->is_satisfied()) {
      on_converged(x, xt, r);
      tolerance_met = criterion_->tolerance_met();
      break;
    }
    x = next_input(x, xt, r);
  }
  if (iterates()) record.criterion_progress = criterion_->progress();
  for (auto& note : take_notes()) notes.push_back(std::move(note));
  record.warnings = count_repeats(notes);
  record.converged = tolerance_met;
  x_.set_data(x);
  return record;
}

void CoupledSolver::synchronize(const Eigen::VectorXd& x) {
  evaluate(x, step_, 0);
}

void CoupledSolver::commit_step(StepRecord& record) {
  predictor_->update(x_.data());
  on_step_end();
  for (int i = 0; i < 2; ++i) timed(i, [&] { solvers_[i]->finalize_step(); });
  for (int i = 0; i < 2; ++i) timed(i, [&] { solvers_[i]->output_step(); });
  // Both solvers commit and write side by side; a failure there still ends this step.
  for (int i = 0; i < 2; ++i) timed(i, [&] { solvers_[i]->complete_step_requests(); });

  unfinished_step_ = 0;
  unfinished_residuals_.clear();
  record.wall_time = seconds_since(step_start_);
  record.solver_times = {solver_time_step_[0], solver_time_step_[1]};
  record.coupler_time =
      record.wall_time - solver_time_step_[0] - solver_time_step_[1] - own_solvers_time_step_;
  record.surrogate_iterations = own_iterations_;
}

void CoupledSolver::save_solver_restarts(int step) {
  for (int i = 0; i < 2; ++i) timed(i, [&] { solvers_[i]->save_restart(step); });
  save_own_solver_restarts(step);
}

Eigen::VectorXd CoupledSolver::evaluate(const Eigen::VectorXd& x, int step, int iteration) {
  x_.set_data(x);
  const Interface& y = timed_solve(0, x_);
  check_finite(y, *solvers_[0], step, iteration);
  y_.set_data(second_solver_input(x, y.data()));
  const Interface& xt = timed_solve(1, y_);
  check_finite(xt, *solvers_[1], step, iteration);
  return xt.data();
}

Eigen::VectorXd CoupledSolver::evaluate_stepping_back(Eigen::VectorXd& x,
                                                      const Eigen::VectorXd& accepted, int step,
                                                      int iteration,
                                                      std::vector<std::string>& notes) {
  std::string first_rejection;  // the one that says what went wrong with the iteration's input
  for (int retry = 1;; ++retry) {
    try {
      return evaluate(x, step, iteration);
    } catch (const SolverRejectedInput& e) {
      if (first_rejection.empty()) first_rejection = e.what();
      if (retry > backtracking_retries_)
        throw SolverError(
            e.solver_name(),
            fmt::format("{}\n(time step {}, coupling iteration {}: the coupled solver stepped "
                        "back {} times towards the last input both solvers accepted, "
                        "coupled_solver.backtracking.retries = {})",
                        first_rejection, step, iteration, backtracking_retries_,
                        backtracking_retries_));
      // The rejected input lies too far from one the solver can take: the step towards it
      // from the last accepted input is too long, whatever made it (a quasi-Newton update
      // from poor secant information, an extrapolating predictor).
      x = accepted + backtracking_factor_ * (x - accepted);
      notes.push_back(fmt::format(
          "solver '{}' rejected the input of iteration {}: the step from the last accepted "
          "input was shortened {} time(s) by {:g}",
          e.solver_name(), iteration, retry, backtracking_factor_));
    }
  }
}

void CoupledSolver::check_finite(const Interface& data, const SolverWrapper& solver, int step,
                                 int iteration) const {
  if (data.data().allFinite()) return;
  for (const auto& block : data.blocks()) {
    const auto values = data.values(block.model_part, block.variable);
    for (Eigen::Index point = 0; point < values.rows(); ++point)
      if (!values.row(point).allFinite())
        throw DivergenceError(DivergenceKind::kNonFinite, step, iteration,
                              fmt::format("solver '{}' returned a non-finite {} at model part "
                                          "'{}', point {} (of {}), in time step {}, coupling "
                                          "iteration {}. {}",
                                          solver.name(), block.variable, block.model_part, point,
                                          values.rows(), step, iteration, divergence_advice()));
  }
}

void CoupledSolver::check_divergence(const std::vector<double>& norms, int step, double time,
                                     std::vector<std::string>& notes) const {
  const double first = norms.front();
  const double last = norms.back();
  const int iteration = static_cast<int>(norms.size());
  if (!std::isfinite(last) || (first > 0.0 && last > divergence_factor_ * first))
    throw DivergenceError(
        std::isfinite(last) ? DivergenceKind::kGrowth : DivergenceKind::kNonFinite, step, iteration,
        fmt::format("the coupling diverged in time step {} (t = {:g} s): the residual norm grew "
                    "from {:.3e} in iteration 1 to {:.3e} in iteration {} (more than "
                    "coupled_solver.divergence.factor = {:g} times). {}",
                    step, time, first, last, norms.size(), divergence_factor_,
                    divergence_advice()));
  // A slow but steady growth never reaches the factor before the iteration limit: catch it by
  // its persistence (converging methods grow at most a few iterations in a row).
  const auto n = static_cast<std::size_t>(growth_iterations_);
  if (n == 0 || norms.size() <= n) return;
  for (std::size_t i = norms.size() - n; i < norms.size(); ++i)
    if (!(norms[i] > norms[i - 1])) return;
  // A stalled iteration creeping up at round-off level is not diverging: ask for a doubling,
  // and for a residual above the noise the solvers' own accuracy leaves (a fraction of the
  // largest first residual of the run: long after a transient, a step's first residual may
  // itself be near that floor, and its iterations wander there).
  if (!(last > 2.0 * norms[norms.size() - 1 - n])) return;
  const double floor = kNoiseFloor * largest_first_residual_;
  if (last <= floor) {
    notes.push_back(fmt::format(
        "the residual grew in each of the last {} iterations but stayed below {:.1e}, {:g} of "
        "the run's largest first residual: the solvers' noise, not a divergence (a stall: "
        "loosen the tolerance or use an absolute criterion)",
        n, floor, kNoiseFloor));
    return;
  }
  throw DivergenceError(
      DivergenceKind::kGrowth, step, iteration,
      fmt::format("the coupling diverged in time step {} (t = {:g} s): the residual norm grew in "
                  "each of the last {} iterations, more than doubling, to {:.3e} in iteration {} "
                  "(coupled_solver.divergence.growth_iterations = {}). {}",
                  step, time, n, last, norms.size(), n, divergence_advice()));
}

void CoupledSolver::save_state(State& state) const {
  const auto& history = predictor_->history();
  Eigen::MatrixXd columns(x_.size(), Eigen::Index(history.size()));
  for (std::size_t i = 0; i < history.size(); ++i) columns.col(Eigen::Index(i)) = history[i];
  state.group("predictor").set("history", std::move(columns));
  state.set("largest_first_residual", largest_first_residual_);
  save_own_state(state);
}

void CoupledSolver::load_state(const State& state, bool own) {
  const Eigen::MatrixXd& columns = state.group("predictor").matrix("history");
  if (columns.rows() != x_.size() || columns.cols() == 0)
    throw std::runtime_error(fmt::format(
        "the saved coupled-solver state holds an interface of {} values, this run's has {} "
        "([{}])",
        columns.rows(), x_.size(), x_.describe()));
  std::deque<Eigen::VectorXd> history;
  for (Eigen::Index i = 0; i < columns.cols(); ++i) history.push_back(columns.col(i));
  predictor_->restore(std::move(history));
  x_.set_data(columns.col(0));
  // (State files written before it was saved lack it: the growth check is then strict.)
  if (state.has("largest_first_residual"))
    largest_first_residual_ = state.scalar("largest_first_residual");
  if (own) load_own_state(state);
}

std::string CoupledSolver::divergence_advice() const {
  return "Strongly coupled problems (light structures, dense fluids) need a quasi-Newton "
         "method: try coupled_solver type 'iqni' with model 'ls', or 'aitken', or a smaller "
         "relaxation factor.";
}

std::string CoupledSolver::describe() const {
  const std::string settings = describe_settings();
  const std::string backtracking =
      backtracking_retries_ == 0
          ? ""
          : fmt::format(", a rejected input retried {} times, the step shortened by {:g}",
                        backtracking_retries_, backtracking_factor_);
  return fmt::format("{}{}, predictor {}, stop at {}{}", type_,
                     settings.empty() ? "" : " (" + settings + ")", predictor_type_,
                     criterion_->describe(), backtracking);
}

}  // namespace cocopp
