#include "coupler/app/run.hpp"

#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <numeric>

#include "core/case/path_problem.hpp"
#include "coupler/app/case.hpp"
#include "coupler/app/case_lock.hpp"
#include "coupler/results/results_writer.hpp"
#include "coupler/results/run_summary.hpp"
#include "coupler/results/state_file.hpp"
#include "coupler/results/vtk_series.hpp"
#include "coupler/results/watchpoint_csv.hpp"
#include "solver_wrappers/process/child_process.hpp"
#include "solver_wrappers/solver_error.hpp"

namespace cocopp {

namespace {

using Clock = std::chrono::steady_clock;

std::atomic<int> interrupt_signal{0};

/// On Ctrl-C or a kill: stop the children at once (async-signal-safe), let the run loop notice
/// the dead solvers, write what it has and exit.
void on_interrupt(int signal) {
  interrupt_signal = signal;
  kill_all_children();
}

/// The results location can be used: a directory, or nothing yet (the run makes it); not a
/// file, a loop of links or a name too long. And cocopp writes only files it creates: a link
/// at a results file's name (planted, or made by hand) would make it overwrite its target.
void check_results_files(const Case& c) {
  if (const auto why = path_problem(c.results_directory, PathKind::kDirectory);
      !why.empty() && why != "does not exist")
    throw std::runtime_error(c.results_where + ": cannot use the directory " +
                             c.results_directory.string() + ": it " + why);
  for (const char* extension : {".h5", ".summary.json", ".state.h5"}) {
    const auto file = c.results_directory / (c.results_name + extension);
    if (std::filesystem::is_symlink(file))
      throw std::runtime_error(file.string() +
                               " is a symbolic link: cocopp writes only files it creates (it "
                               "would overwrite the link's target); remove the link");
  }
}

void print_header(const Case& c) {
  fmt::print("cocopp {}: case {}\n", COCOPP_VERSION, c.file.string());
  fmt::print("  time steps     : {} .. {} of delta_t {:g} s (t = {:g} .. {:g} s)\n",
             c.run.timestep_start + 1, c.run.timestep_start + c.run.number_of_timesteps,
             c.run.delta_t, c.run.timestep_start * c.run.delta_t, c.end_time());
  fmt::print("  coupled solver : {}\n", c.coupled_solver->describe());
  for (std::size_t i = 0; i < c.solvers.size(); ++i)
    fmt::print("  solver {}       : {}\n", i + 1, c.solvers[i]->describe());
  fmt::print("  results        : {}{}\n", (c.results_directory / c.results_name).string() + ".h5",
             c.restart ? fmt::format(" (continued after step {})", c.restart->step) : "");
  if (c.restart)
    fmt::print("  restart        : after step {} (t = {:g} s) from {}\n", c.restart->step,
               c.restart->time, c.state_file().string());
}

RunDescription describe_run(const Case& c) {
  RunDescription d;
  d.case_file = c.file.string();
  d.coupled_solver = c.coupled_solver_type;
  for (const auto& s : c.solvers) d.solver_names.push_back(s->name());
  d.delta_t = c.run.delta_t;
  d.timestep_start = c.run.timestep_start;
  d.number_of_timesteps = c.run.number_of_timesteps;
  d.restarted = c.restart.has_value();
  d.convergence_criterion = c.coupled_solver->criterion().describe();
  d.tolerances = c.coupled_solver->criterion().tolerances();
  return d;
}

/// "42 s", "3 min 20 s", "2 h 05 min".
std::string duration(double seconds) {
  const long s = std::lround(seconds);
  if (s < 60) return fmt::format("{} s", s);
  if (s < 3600) return fmt::format("{} min {:02} s", s / 60, s % 60);
  return fmt::format("{} h {:02} min", s / 3600, (s % 3600) / 60);
}

/// One line per time step: the residual (2-norm, and as the criterion measures it where that
/// differs: "relative 3.1e-07"), the step's wall time, and the time left at the average pace
/// of the steps so far.
void print_progress(const StepRecord& r, int last_step, double seconds_left) {
  const std::string criterion =
      r.criterion_progress.empty() ? "" : " (" + r.criterion_progress + ")";
  const std::string surrogate =
      r.surrogate_iterations > 0 ? fmt::format("  (surrogate {:>2})", r.surrogate_iterations) : "";
  const std::string left = r.step < last_step ? "  left " + duration(seconds_left) : "";
  fmt::print(
      "step {:>{}} / {}  t = {:<10.4g} iterations {:>3}  residual {:.3e}{}{}  {:8.3f} ms{}{}\n",
      r.step, std::to_string(last_step).size(), last_step, r.time, r.iterations,
      r.residual_norms.back(), r.converged ? " " : "*", criterion, 1e3 * r.wall_time, surrogate,
      left);
  std::fflush(stdout);
}

/// `--verbose`: one line per coupling iteration, indented under the step's line to come.
void print_iteration(const IterationReport& r) {
  fmt::print("    step {} iteration {:>3}  residual {:.3e}{}  {:.3f} s into the step\n", r.step,
             r.iteration, r.residual, r.criterion.empty() ? "" : " (" + r.criterion + ")",
             r.step_seconds);
  std::fflush(stdout);
}

class Run {
 public:
  explicit Run(Case& c) : case_(c), summary_(describe_run(c)) {}

  RunOutcome execute(const RunOptions& options) {
    silent_ = options.silent;
    RunOutcome outcome;
    try {
      march(options);
      outcome = went_through();
    } catch (const DivergenceError& e) {
      outcome = stopped(RunStatus::kDiverged, e.what());
      outcome.divergence = e.kind;
      outcome.step = e.step;
      outcome.iteration = e.iteration;
      outcome.reason =
          fmt::format("{} in step {}, iteration {}", to_string(e.kind), e.step, e.iteration);
    } catch (const SolverError& e) {
      outcome = stopped(RunStatus::kSolverFailed, e.what());
    } catch (const std::exception& e) {
      outcome = stopped(RunStatus::kFailed, e.what());
    }
    if (interrupt_signal != 0)
      outcome = stopped(RunStatus::kInterrupted,
                        fmt::format("interrupted by signal {} ({})", interrupt_signal.load(),
                                    strsignal(interrupt_signal)));
    stop_solvers(outcome);
    finish(outcome);
    return outcome;
  }

  const RunSummary& summary() const { return summary_; }
  std::filesystem::path results_file() const { return results_path(".h5"); }

 private:
  void march(const RunOptions& options) {
    CoupledSolver& coupled = *case_.coupled_solver;
    coupled.initialize(*case_.solvers[0], *case_.solvers[1]);
    if (!silent_)
      fmt::print("  started        : {}, {}\n", case_.solvers[0]->started(),
                 case_.solvers[1]->started());
    const int continue_after = case_.restart ? case_.restart->step : -1;
    if (!case_.watchpoints.empty()) {
      case_.watchpoints.attach(coupled.x(), coupled.y());
      watchpoint_csv_ = std::make_unique<WatchpointCsv>(case_.results_directory, case_.results_name,
                                                        case_.watchpoints.layout(), continue_after);
    }
    if (case_.restart) {
      coupled.load_state(case_.restart->state, !options.fresh_coupling);
      writer_ = std::make_unique<ResultsWriter>(results_path(".h5"), describe_run(case_),
                                                coupled.x(), coupled.y(), case_.restart->step,
                                                case_.watchpoints.layout());
    } else {
      writer_ =
          std::make_unique<ResultsWriter>(results_path(".h5"), describe_run(case_), coupled.x(),
                                          coupled.y(), case_.watchpoints.layout());
    }
    writer_->set_write_interval(case_.results_write_interval);
    if (case_.vtk_output)
      vtk_ = std::make_unique<VtkSeries>(case_.results_directory, case_.results_name,
                                         case_.restart ? case_.restart->step : -1);
    const bool verbose = options.verbose;
    if (verbose || !case_.vtk_iterations.empty())
      coupled.set_iteration_observer([this, verbose](const IterationReport& report) {
        if (verbose) print_iteration(report);
        write_iteration_vtk(report);
      });
    const int first = case_.run.timestep_start + 1;
    const int last = case_.run.timestep_start + case_.run.number_of_timesteps;
    const auto march_start = std::chrono::steady_clock::now();
    for (int step = first; step <= last; ++step) {
      current_step_ = step;
      const StepRecord record = coupled.solve_step(step, step * case_.run.delta_t);
      // No watchpoints: an empty interface, which the writer leaves out.
      const Interface& watched = case_.watchpoints.sample(coupled.x(), coupled.y());
      writer_->write_step(record, coupled.x(), coupled.y(), watched);
      if (watchpoint_csv_) watchpoint_csv_->write_step(step, record.time, watched);
      if (vtk_) vtk_->write_step(step, record.time, vtk_parts(coupled.x(), coupled.y()));
      summary_.add_step(record);
      iterations_ += record.iterations;
      algorithm_time_ += record.coupler_time;
      if (!options.quiet && !silent_) {
        const std::chrono::duration<double> elapsed =
            std::chrono::steady_clock::now() - march_start;
        print_progress(record, last, elapsed.count() / (step - first + 1) * (last - step));
      }
      print_warnings(record);
      // The last step is saved once, after the loop.
      if (case_.state_interval > 0 && step < last && step % case_.state_interval == 0)
        save_state(step);
    }
    save_state(last);
    current_step_ = 0;
  }

  /// settings.vtk_iterations: the iteration's x, y and residual r = x~ - x of a chosen step, as
  /// <name>_step<step>_iterations.pvd with the iteration number as its time.
  void write_iteration_vtk(const IterationReport& report) {
    const auto& chosen = case_.vtk_iterations;
    if (std::find(chosen.begin(), chosen.end(), report.step) == chosen.end()) return;
    const CoupledSolver& coupled = *case_.coupled_solver;
    if (report.iteration == 1 || !iteration_vtk_)
      iteration_vtk_ = std::make_unique<VtkSeries>(
          case_.results_directory,
          fmt::format("{}_step{:06d}_iterations", case_.results_name, report.step));
    std::vector<VtkPart> parts = vtk_parts(coupled.x(), coupled.y());
    Interface residual = coupled.x();
    residual.set_data(*report.residual_vector);
    add_vtk_fields(parts, residual, "residual_");
    iteration_vtk_->write_step(report.iteration, report.iteration, parts);
  }

  /// Every step computed: completed, or stalled if some were accepted at the iteration limit.
  RunOutcome went_through() const {
    RunOutcome outcome;
    const auto& unconverged = summary_.unconverged_steps();
    if (unconverged.empty()) return outcome;
    outcome.status = RunStatus::kStalled;
    outcome.reason = fmt::format("{} of {} steps at the iteration limit", unconverged.size(),
                                 summary_.steps_completed());
    return outcome;
  }

  /// A run that stopped in the step it was computing (or before the first, or after the last).
  RunOutcome stopped(RunStatus status, const std::string& message) const {
    RunOutcome outcome;
    outcome.status = status;
    outcome.message = message;
    outcome.step = current_step_;
    const std::string where =
        current_step_ > 0
            ? fmt::format("in step {}", current_step_)
            : (summary_.steps_completed() > 0 ? "after the last step" : "at start-up");
    outcome.reason = fmt::format("{} {}", status_text(status), where);
    return outcome;
  }

  static const char* status_text(RunStatus status) {
    switch (status) {
      case RunStatus::kSolverFailed:
        return "solver failure";
      case RunStatus::kInterrupted:
        return "interrupted";
      default:
        return "error";
    }
  }

  /// The first few steps' warnings as they come; all of them go to the summary.
  void print_warnings(const StepRecord& record) {
    constexpr int kPrintedSteps = 5;
    if (silent_ || record.warnings.empty() || ++steps_with_warnings_ > kPrintedSteps + 1) return;
    if (steps_with_warnings_ > kPrintedSteps) {
      fmt::print("warning: more steps with warnings follow: see \"warnings\" in {}\n",
                 results_path(".summary.json").string());
      return;
    }
    for (const auto& warning : record.warnings)
      fmt::print("warning: step {}: {}\n", record.step, warning);
  }

  /// Between steps only: in the middle of a step the models hold half a step's columns.
  void save_state(int step) {
    // A restart continues the results file after the state's step: it must be in the file.
    writer_->write_kept_steps();
    // The solvers first: a state file always has the solvers' restart data behind it.
    case_.coupled_solver->save_solver_restarts(step);
    SavedState saved;
    saved.step = step;
    saved.time = step * case_.run.delta_t;
    saved.coupled_solver = case_.coupled_solver->describe();
    case_.coupled_solver->save_state(saved.state);
    write_state_file(case_.state_file(), saved);
    state_saved_ = true;
  }

  void stop_solvers(RunOutcome& outcome) {
    auto stop = [&](auto finalize) {
      try {
        finalize();
      } catch (const std::exception& e) {
        if (ran_all_steps(outcome.status)) outcome = stopped(RunStatus::kSolverFailed, e.what());
      }
    };
    for (auto& solver : case_.solvers) stop([&] { solver->finalize(); });
    stop([&] { case_.coupled_solver->finalize(); });  // its own solvers (a surrogate's)
  }

  std::filesystem::path results_path(const std::string& extension) const {
    return case_.results_directory / (case_.results_name + extension);
  }

  /// Results that cannot be written (a disk that filled up, a directory that went away) end
  /// the run as failed, with the reason; never an exception out of the run.
  void note_write_failure(RunOutcome& outcome, const std::exception& error) const {
    if (!outcome.message.empty()) {
      outcome.message += "\n(and: " + std::string(error.what()) + ")";
      return;
    }
    outcome = stopped(RunStatus::kFailed, error.what());
    outcome.reason = "the results could not be written";
  }

  void finish(RunOutcome& outcome) {
    const double wall = std::chrono::duration<double>(Clock::now() - start_).count();
    const auto& solver_times = case_.coupled_solver->solver_time_total();
    const double own_solvers = case_.coupled_solver->own_solvers_time_total();
    const double coupler = wall - solver_times[0] - solver_times[1] - own_solvers;
    try {
      const CoupledSolver& coupled = *case_.coupled_solver;
      if (writer_ && coupled.unfinished_step() > 0)
        writer_->write_unfinished_step(coupled.unfinished_step(),
                                       coupled.unfinished_step() * case_.run.delta_t,
                                       coupled.unfinished_residuals());
      if (writer_) writer_->close(to_string(outcome.status), outcome.message);
    } catch (const std::exception& e) {
      note_write_failure(outcome, e);
    }
    summary_.finish(outcome, wall, {solver_times[0], solver_times[1]}, coupler);
    try {
      summary_.write(results_path(".summary.json"));
    } catch (const std::exception& e) {
      note_write_failure(outcome, e);
    }

    const int steps = writer_ ? writer_->steps_written() : 0;
    if (silent_) return;  // the caller reports the outcome
    fmt::print("\n{} after {} time step{} in {:.3f} s{}\n", to_string(outcome.status), steps,
               steps == 1 ? "" : "s", wall, outcome.reason.empty() ? "" : ": " + outcome.reason);
    auto line = [](const std::string& label, const std::string& text) {
      fmt::print("  {:<18}: {}\n", label, text);
    };
    for (std::size_t i = 0; i < 2; ++i)
      line("solver " + case_.solvers[i]->name(), fmt::format("{:.3f} s", solver_times[i]));
    if (own_solvers > 0.0)
      line("surrogate", fmt::format("{:.3f} s (its solvers and coupling)", own_solvers));
    line("coupler", fmt::format("{:.3f} s ({:.1f} us per coupling iteration inside the steps)",
                                coupler, iterations_ ? 1e6 * algorithm_time_ / iterations_ : 0.0));
    if (steps > 0)
      line("iterations", fmt::format("{:.2f} per time step on average ({} in all)",
                                     double(iterations_) / steps, iterations_));
    if (writer_) line("results", writer_->path().string());
    if (vtk_) line("ParaView", vtk_->collection().string());
    if (watchpoint_csv_)
      for (const auto& file : watchpoint_csv_->files()) line("watchpoint", file.string());
    if (state_saved_) line("solver state", results_path(".state.h5").string());
    line("summary", results_path(".summary.json").string());
    std::fflush(stdout);  // the error comes last, after the summary, also when piped
    if (!outcome.message.empty()) fmt::print(stderr, "\nerror: {}\n", outcome.message);
  }

  Case& case_;
  RunSummary summary_;
  std::unique_ptr<ResultsWriter> writer_;
  std::unique_ptr<VtkSeries> vtk_;
  std::unique_ptr<VtkSeries> iteration_vtk_;  ///< the chosen step being computed
  std::unique_ptr<WatchpointCsv> watchpoint_csv_;
  Clock::time_point start_ = Clock::now();
  bool silent_ = false;
  long iterations_ = 0;
  double algorithm_time_ = 0.0;
  bool state_saved_ = false;
  int steps_with_warnings_ = 0;
  int current_step_ = 0;  ///< the step being computed; 0 outside the time loop
};

}  // namespace

namespace {
/// An error's text for the user: a std::filesystem error (a path no check above caught) in
/// words, not as "filesystem error: status: ...".
std::string error_message(const std::exception& error) {
  if (const auto* fs_error = dynamic_cast<const std::filesystem::filesystem_error*>(&error))
    return describe_filesystem_error(*fs_error);
  return error.what();
}
}  // namespace

/// A run that never started: the error printed, nothing written.
RunReport not_started(RunStatus status, const char* reason, const std::exception& error) {
  const std::string message = error_message(error);
  fmt::print(stderr, "error: {}\n", message);
  RunReport report;
  report.outcome.status = status;
  report.outcome.message = message;
  report.outcome.reason = reason;
  return report;
}

RunReport run_case(const std::filesystem::path& case_file, const RunOptions& options) {
  RunReport report;
  Case c;
  try {
    c = load_case(case_file, options.restart);
    for (const auto& solver : c.solvers) solver->check();
  } catch (const std::exception& e) {
    return not_started(RunStatus::kInvalidCase, "invalid case", e);
  }
  // Before anything is written or started: one run of a case at a time, and a results
  // directory that can be written.
  std::unique_ptr<CaseLock> lock;
  try {
    check_results_files(c);
    std::vector<std::filesystem::path> lock_files{c.results_directory / (c.results_name + ".lock")};
    for (const auto& directory : c.working_directories)
      lock_files.push_back(directory / ".cocopp.lock");
    lock = std::make_unique<CaseLock>(lock_files);
  } catch (const std::exception& e) {
    return not_started(RunStatus::kFailed, "the case cannot be run now", e);
  }
  if (!options.silent) print_header(c);
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  std::signal(SIGHUP, on_interrupt);
  Run run(c);
  report.outcome = run.execute(options);
  report.summary = run.summary();
  report.results_file = run.results_file();
  return report;
}

int check_case(const std::filesystem::path& case_file) {
  try {
    const Case c = load_case(case_file);
    for (const auto& solver : c.solvers) {
      solver->check();
      solver->check_solver_input();
    }
    check_results_files(c);
    fmt::print("{}: OK\n", case_file.string());
    print_header(c);
    return 0;
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", error_message(e));
    return 2;
  }
}

}  // namespace cocopp
