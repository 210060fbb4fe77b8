#include "coupler/coupled_solvers/coupled_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

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
      backtracking_{settings.child_or_empty("backtracking").get_int_in_range("retries", 4, 0),
                    settings.child_or_empty("backtracking")
                        .get_in_range("factor", 0.5, {0.0, 1.0, true, true})} {}

CoupledSolver::~CoupledSolver() = default;

void CoupledSolver::initialize(SolverWrapper& first, SolverWrapper& second) {
  scheme_ = std::make_unique<SerialScheme>(first, second, backtracking_, divergence_advice());
  scheme_->set_loads_update([this](const Eigen::VectorXd& x, const Eigen::VectorXd& yt) {
    return second_solver_input(x, yt);
  });
  scheme_->start();
  predictor_->initialize(scheme_->x().data());
  criterion_->attach_solvers(scheme_->solvers());
  on_initialized();
}

const Interface& CoupledSolver::x() const {
  static const Interface none;
  return scheme_ ? scheme_->x() : none;
}

const Interface& CoupledSolver::y() const {
  static const Interface none;
  return scheme_ ? scheme_->y() : none;
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
  own_solvers_time_step_ = 0.0;
  own_iterations_ = 0;
  StepRecord record;
  record.step = step;
  record.time = time;
  unfinished_step_ = step;
  unfinished_residuals_.clear();
  scheme_->begin_step(step, time);

  // The previous step's converged input: what the solvers last accepted.
  Eigen::VectorXd accepted = scheme_->x().data();
  criterion_->initialize_step();
  on_step_start();
  Eigen::VectorXd x = first_input(predictor_->predict());
  bool tolerance_met = false;
  std::vector<std::string> notes;
  for (int iteration = 1;; ++iteration) {
    const Eigen::VectorXd xt = scheme_->evaluate_stepping_back(x, accepted, iteration, notes);
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
                           seconds_since(step_start_), &scheme_->x().data(), &scheme_->y().data(),
                           &r});
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
  scheme_->set_x(x);
  return record;
}

void CoupledSolver::synchronize(const Eigen::VectorXd& x) {
  scheme_->evaluate(x, 0);
}

void CoupledSolver::commit_step(StepRecord& record) {
  predictor_->update(scheme_->x().data());
  on_step_end();
  scheme_->commit_step();

  unfinished_step_ = 0;
  unfinished_residuals_.clear();
  record.wall_time = seconds_since(step_start_);
  const auto& solver_times = scheme_->step_times();
  record.solver_times = {solver_times[0], solver_times[1]};
  record.coupler_time =
      record.wall_time - solver_times[0] - solver_times[1] - own_solvers_time_step_;
  record.surrogate_iterations = own_iterations_;
  record.x = scheme_->x().data();
  record.y = scheme_->y().data();
}

void CoupledSolver::save_solver_restarts(int step) {
  scheme_->save_restarts(step);
  save_own_solver_restarts(step);
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
  Eigen::MatrixXd columns(x().size(), Eigen::Index(history.size()));
  for (std::size_t i = 0; i < history.size(); ++i) columns.col(Eigen::Index(i)) = history[i];
  state.group("predictor").set("history", std::move(columns));
  state.set("largest_first_residual", largest_first_residual_);
  save_own_state(state);
}

void CoupledSolver::load_state(const State& state, bool own) {
  const Eigen::MatrixXd& columns = state.group("predictor").matrix("history");
  if (columns.rows() != x().size() || columns.cols() == 0)
    throw std::runtime_error(fmt::format(
        "the saved coupled-solver state holds an interface of {} values, this run's has {} "
        "([{}])",
        columns.rows(), x().size(), x().describe()));
  std::deque<Eigen::VectorXd> history;
  for (Eigen::Index i = 0; i < columns.cols(); ++i) history.push_back(columns.col(i));
  predictor_->restore(std::move(history));
  scheme_->set_x(columns.col(0));
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
      backtracking_.retries == 0
          ? ""
          : fmt::format(", a rejected input retried {} times, the step shortened by {:g}",
                        backtracking_.retries, backtracking_.factor);
  return fmt::format("{}{}, predictor {}, stop at {}{}", type_,
                     settings.empty() ? "" : " (" + settings + ")", predictor_type_,
                     criterion_->describe(), backtracking);
}

}  // namespace cocopp
