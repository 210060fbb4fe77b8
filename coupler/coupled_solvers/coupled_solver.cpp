#include "coupler/coupled_solvers/coupled_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/case/suggest.hpp"

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

/// The `scheme` key: one of the registered coupling schemes.
std::string read_scheme(const Settings& settings) {
  const auto scheme = settings.get<std::string>("scheme", "serial");
  const auto names = CouplingSchemeRegistry::instance().names();
  if (std::find(names.begin(), names.end(), scheme) == names.end())
    settings.fail("scheme", "unknown coupling scheme '" + scheme + "'" +
                                did_you_mean(scheme, names) + " (available: " + join(names) + ")");
  return scheme;
}

std::unique_ptr<ConvergenceCriterion> read_load_criterion(const Settings& settings,
                                                          const std::string& scheme) {
  if (!settings.has("load_criterion")) {
    if (scheme == "parallel")
      settings.fail("scheme",
                    "parallel needs a load_criterion too: side by side the displacement residual "
                    "S(y) - x can vanish while y is not yet F(x) (add e.g. load_criterion: {type: "
                    "value_relative_norm, tolerance: 1.0e-8}, and measure the displacement so "
                    "too: docs/coupling.md, \"Schemes\")");
    return nullptr;
  }
  if (scheme != "parallel")
    settings.fail("load_criterion",
                  "measures the load residual y~ - y, which only the parallel scheme iterates on "
                  "(set scheme: parallel, or remove load_criterion)");
  return ConvergenceCriterionRegistry::instance().create(settings.child("load_criterion"));
}
/// `time_interpolation`: how a solver that takes substeps gets the other's values between
/// the other's samples (Waveform).
Waveform::Interpolation read_time_interpolation(const Settings& settings) {
  const std::string name =
      settings.get_choice("time_interpolation", "linear", {"constant", "linear", "quadratic"});
  if (name == "constant") return Waveform::Interpolation::kConstant;
  return name == "linear" ? Waveform::Interpolation::kLinear : Waveform::Interpolation::kQuadratic;
}
}  // namespace

CoupledSolver::CoupledSolver(const Settings& settings)
    : type_(settings.required<std::string>("type")),
      scheme_type_(read_scheme(settings)),
      scheme_settings_(settings),
      predictor_type_(settings.child("predictor").required<std::string>("type")),
      predictor_(PredictorRegistry::instance().create(settings.child("predictor"))),
      criterion_(
          ConvergenceCriterionRegistry::instance().create(settings.child("convergence_criterion"))),
      load_criterion_(read_load_criterion(settings, scheme_type_)),
      divergence_factor_(
          settings.child_or_empty("divergence").get_in_range("factor", 1e6, Range::at_least(1.0))),
      growth_iterations_(
          settings.child_or_empty("divergence").get_int_in_range("growth_iterations", 10, 0)),
      time_interpolation_(read_time_interpolation(settings)),
      time_average_(settings.get<bool>("time_average", true)),
      backtracking_{settings.child_or_empty("backtracking").get_int_in_range("retries", 4, 0),
                    settings.child_or_empty("backtracking")
                        .get_in_range("factor", 0.5, {0.0, 1.0, true, true})} {}

CoupledSolver::~CoupledSolver() = default;

void CoupledSolver::initialize(SolverWrapper& first, SolverWrapper& second) {
  check_solvers(first, second);
  scheme_ = CouplingSchemeRegistry::instance().create_named(
      scheme_type_, scheme_settings_,
      CouplingScheme::Parts{&first, &second, backtracking_, divergence_advice(),
                            time_interpolation_, time_average_});
  scheme_->set_loads_update([this](const Eigen::VectorXd& x, const Eigen::VectorXd& yt) {
    return second_solver_input(x, yt);
  });
  scheme_->start();
  predictor_->initialize(scheme_->unknown());
  criterion_->attach_solvers(scheme_->solvers());
  on_initialized();
}

void CoupledSolver::check_solvers(const SolverWrapper& first, const SolverWrapper& second) const {
  for (const SolverWrapper* solver : {&first, &second}) {
    if (solver->substeps() == 1) continue;
    const std::string takes = "solver '" + solver->name() + "' takes " +
                              std::to_string(solver->substeps()) + " substeps a time step";
    if (!takes_substeps())
      scheme_settings_.fail("type", "coupled solver '" + type_ +
                                        "' cannot iterate on windows of substeps (" + takes +
                                        "): use iqni, aitken, relaxation or gauss_seidel");
    if (side_by_side())
      scheme_settings_.fail("scheme", takes +
                                          ", which the parallel scheme does not yet iterate on: "
                                          "use scheme serial");
  }
}

const Interface& CoupledSolver::x() const {
  static const Interface none;
  return scheme_ ? scheme_->x() : none;
}

const Interface& CoupledSolver::y() const {
  static const Interface none;
  return scheme_ ? scheme_->y() : none;
}

std::vector<const Interface*> CoupledSolver::unknown_layouts() const {
  return scheme_ ? scheme_->unknown_layouts() : std::vector<const Interface*>{};
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

  // The previous step's converged unknown: what the solvers last accepted.
  Eigen::VectorXd accepted = scheme_->unknown();
  criterion_->initialize_step();
  if (load_criterion_) load_criterion_->initialize_step();
  on_step_start();
  Eigen::VectorXd u = first_input(predictor_->predict());
  bool tolerance_met = false;
  std::vector<std::string> notes;
  for (int iteration = 1;; ++iteration) {
    const Eigen::VectorXd ut = scheme_->evaluate_stepping_back(u, accepted, iteration, notes);
    accepted = u;
    const Eigen::VectorXd r = ut - u;
    // The displacement residual x~ - x is what every scheme reports and checks.
    const Eigen::VectorXd rx = scheme_->displacement_part(r);
    record.residual_norms.push_back(rx.norm());
    unfinished_residuals_.push_back(record.residual_norms.back());
    record.iterations = iteration;
    if (iteration == 1) largest_first_residual_ = std::max(largest_first_residual_, rx.norm());
    check_divergence(record.residual_norms, step, time, notes);
    if (!iterates()) {
      u = ut;  // explicit coupling accepts the solvers' answers
      tolerance_met = true;
      break;
    }
    const bool stop = update_criteria(r, ut, tolerance_met);
    // The progress text is formatted for an observer, else once for the step's last iteration:
    // formatting it every iteration cost 7 % of the coupler's time on the tube.
    if (iteration_observer_)
      iteration_observer_({step, iteration, record.residual_norms.back(), criterion_->progress(),
                           seconds_since(step_start_), &scheme_->x().data(), &scheme_->y().data(),
                           &rx});
    if (stop) {
      on_converged(u, ut, r);
      break;
    }
    u = next_input(u, ut, r);
  }
  if (iterates()) record.criterion_progress = progress();
  if (iterates() && !tolerance_met && record.residual_norms.back() <= noise_floor()) {
    record.at_noise = true;
    notes.push_back(fmt::format(
        "the iteration limit with the residual {:.3e} at the solvers' noise (below {:.1e}): the "
        "criterion cannot be met there; the step is taken as it is (an absolute criterion above "
        "the noise ends such steps at once)",
        record.residual_norms.back(), noise_floor()));
  }
  for (auto& note : take_notes()) notes.push_back(std::move(note));
  record.warnings = count_repeats(notes);
  record.converged = tolerance_met;
  scheme_->set_unknown(u);
  return record;
}

std::string CoupledSolver::progress() const {
  const std::string displacement = criterion_->progress();
  if (!load_criterion_) return displacement;
  // Side by side the loads' residual is the other half of the story.
  const std::string measured = load_criterion_->progress();
  const std::string loads =
      "loads " + (measured.empty() ? fmt::format("{:.3e}", last_load_residual_) : measured);
  return displacement.empty() ? loads : displacement + ", " + loads;
}

bool CoupledSolver::update_criteria(const Eigen::VectorXd& r, const Eigen::VectorXd& ut,
                                    bool& tolerance_met) {
  criterion_->set_output(scheme_->displacement_part(ut));
  criterion_->update(convergence_residual(scheme_->displacement_part(r)));
  if (!load_criterion_) {
    tolerance_met = criterion_->tolerance_met();
    return criterion_->is_satisfied();
  }
  const Eigen::VectorXd ry = scheme_->loads_part(r);
  load_criterion_->set_output(scheme_->loads_part(ut));
  load_criterion_->update(ry);
  last_load_residual_ = ry.norm();
  tolerance_met = criterion_->tolerance_met() && load_criterion_->tolerance_met();
  // An iteration limit in either criterion ends the step; a tolerance needs both.
  return tolerance_met || criterion_->limit_reached() || load_criterion_->limit_reached();
}

double CoupledSolver::noise_floor() const {
  // The interface's size: the diagonal of the box around the displacement interface's points.
  Eigen::RowVector3d low = Eigen::RowVector3d::Constant(std::numeric_limits<double>::max());
  Eigen::RowVector3d high = -low;
  for (const auto& part : scheme_->x().parts()) {
    const Coordinates& points = part.model_part->coordinates;
    if (points.rows() == 0) continue;
    low = low.cwiseMin(points.colwise().minCoeff());
    high = high.cwiseMax(points.colwise().maxCoeff());
  }
  const double size = (high.array() >= low.array()).all() ? (high - low).norm() : 0.0;
  const double values = static_cast<double>(scheme_->x().size());
  return std::max(kNoiseFloor * largest_first_residual_, kRoundOff * size * std::sqrt(values));
}

void CoupledSolver::synchronize(const Eigen::VectorXd& u) {
  scheme_->evaluate(u, 0);
}

void CoupledSolver::commit_step(StepRecord& record) {
  predictor_->update(scheme_->unknown());
  on_step_end();
  scheme_->commit_step();

  unfinished_step_ = 0;
  unfinished_residuals_.clear();
  record.wall_time = seconds_since(step_start_);
  const auto& solver_times = scheme_->step_times();
  record.solver_times = {solver_times[0], solver_times[1]};
  record.coupler_time =
      record.wall_time - scheme_->step_solvers_wall_time() - own_solvers_time_step_;
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
  // Side by side, the first displacement residual can be near zero while the loads' is not
  // (relative_norm's `reference`): growth is measured from the larger of the first two.
  const int reference = side_by_side() && norms.size() > 1 && norms[1] > norms[0] ? 1 : 0;
  const double first = norms[std::size_t(reference)];
  const double last = norms.back();
  const int iteration = static_cast<int>(norms.size());
  if (!std::isfinite(last) || (first > 0.0 && last > divergence_factor_ * first))
    throw DivergenceError(
        std::isfinite(last) ? DivergenceKind::kGrowth : DivergenceKind::kNonFinite, step, iteration,
        fmt::format("the coupling diverged in time step {} (t = {:g} s): the residual norm grew "
                    "from {:.3e} in iteration {} to {:.3e} in iteration {} (more than "
                    "coupled_solver.divergence.factor = {:g} times). {}",
                    step, time, first, reference + 1, last, norms.size(), divergence_factor_,
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
  Eigen::MatrixXd columns(scheme_->unknown().size(), Eigen::Index(history.size()));
  for (std::size_t i = 0; i < history.size(); ++i) columns.col(Eigen::Index(i)) = history[i];
  state.group("predictor").set("history", std::move(columns));
  state.set("largest_first_residual", largest_first_residual_);
  save_own_state(state);
}

void CoupledSolver::load_state(const State& state, bool own) {
  const Eigen::MatrixXd columns =
      predictor_history(state.group("predictor").matrix("history"), own);
  std::deque<Eigen::VectorXd> history;
  for (Eigen::Index i = 0; i < columns.cols(); ++i) history.push_back(columns.col(i));
  predictor_->restore(std::move(history));
  scheme_->set_unknown(columns.col(0));
  // (State files written before it was saved lack it: the growth check is then strict.)
  if (state.has("largest_first_residual"))
    largest_first_residual_ = state.scalar("largest_first_residual");
  if (own) load_own_state(state);
}

Eigen::MatrixXd CoupledSolver::predictor_history(const Eigen::MatrixXd& saved, bool own) const {
  const Eigen::Index size = scheme_->unknown().size(), nx = x().size();
  if (saved.rows() == size && saved.cols() > 0) return saved;
  // A fresh coupled solver may continue another scheme's run: side by side after serial, the
  // loads' history is the loads the first solver reports now (the predictor extrapolates
  // them from there); serial after side by side, the displacement's part.
  if (!own && saved.cols() > 0 && saved.rows() == nx && side_by_side()) {
    Eigen::MatrixXd stacked(size, saved.cols());
    stacked.topRows(nx) = saved;
    stacked.bottomRows(size - nx).colwise() = y().data();
    return stacked;
  }
  if (!own && saved.cols() > 0 && saved.rows() == nx + y().size() && !side_by_side())
    return saved.topRows(nx);
  throw std::runtime_error(fmt::format(
      "the saved coupled-solver state holds an unknown of {} values, this run's has {} "
      "([{}]{}; a run saved by one coupling scheme continues with the same scheme, or with "
      "another after --fresh-coupling)",
      saved.rows(), size, x().describe(),
      side_by_side() ? " and [" + y().describe() + "], scheme parallel" : ""));
}

std::string CoupledSolver::quasi_newton_advice(double omega) {
  return fmt::format(
      "A quasi-Newton method diverges from a poor first update or from secant information that "
      "no longer fits: relax the first update more (omega {:g}; try {:g}), reuse fewer earlier "
      "steps (the model's q) or drop noisy columns (min_significant), or take a smaller "
      "delta_t.",
      omega, omega / 10);
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
  const std::string scheme = side_by_side() ? ", the solvers side by side (scheme parallel)" : "";
  const std::string loads =
      load_criterion_ ? " and, of the loads, " + load_criterion_->describe() : "";
  return fmt::format("{}{}{}, predictor {}, stop at {}{}{}", type_,
                     settings.empty() ? "" : " (" + settings + ")", scheme, predictor_type_,
                     criterion_->describe(), loads, backtracking);
}

}  // namespace cocopp
