#include "coupler/app/run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <numeric>

#include "core/case/path_problem.hpp"
#include "coupler/app/case.hpp"
#include "coupler/app/case_lock.hpp"
#include "coupler/outputs/progress_output.hpp"
#include "coupler/outputs/summary_output.hpp"
#include "coupler/results/state_file.hpp"
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
  if (const auto why = creation_problem(c.files.directory); !why.empty())
    throw std::runtime_error(c.results_where + ": cannot use the directory " +
                             c.files.directory.string() + ": it " + why);
  for (const auto& file : c.files.replaced())
    if (std::filesystem::is_symlink(file))
      throw std::runtime_error(file.string() +
                               " is a symbolic link: cocopp writes only files it creates (it "
                               "would overwrite the link's target); remove the link");
}

void print_header(const Case& c) {
  fmt::print("cocopp {}: case {}\n", COCOPP_VERSION, c.file.string());
  fmt::print("  time steps     : {} .. {} of delta_t {:g} s (t = {:g} .. {:g} s)\n",
             c.run.timestep_start + 1, c.run.timestep_start + c.run.number_of_timesteps,
             c.run.delta_t, c.run.timestep_start * c.run.delta_t, c.end_time());
  fmt::print("  coupled solver : {}\n", c.coupled_solver->describe());
  for (std::size_t i = 0; i < c.solvers.size(); ++i)
    fmt::print("  solver {}       : {}\n", i + 1, c.solvers[i]->describe());
  fmt::print("  results        : {}{}\n", c.files.results().string(),
             c.restart ? fmt::format(" (continued after step {})", c.restart->step) : "");
  if (c.restart)
    fmt::print("  restart        : after step {} (t = {:g} s) from {}\n", c.restart->step,
               c.restart->time, c.files.state().string());
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

/// One run of a case: start the solvers, march in time feeding every output, save the state,
/// stop the solvers, close the outputs and print how it went.
class Run {
 public:
  Run(Case& c, const RunOptions& options)
      : case_(c),
        options_(options),
        summary_(describe_run(c), c.files),
        progress_(!options.quiet && !options.silent, options.verbose, !options.silent) {}

  RunOutcome execute() {
    RunOutcome outcome;
    try {
      march();
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

  const RunSummary& summary() const { return summary_.summary(); }

 private:
  void march() {
    CoupledSolver& coupled = *case_.coupled_solver;
    coupled.initialize(*case_.solvers[0], *case_.solvers[1]);
    if (!options_.silent)
      fmt::print("  started        : {}, {}\n", case_.solvers[0]->started(),
                 case_.solvers[1]->started());
    if (case_.restart) coupled.load_state(case_.restart->state, !options_.fresh_coupling);
    open_outputs();
    const int first = case_.run.timestep_start + 1;
    const int last = case_.run.timestep_start + case_.run.number_of_timesteps;
    for (int step = first; step <= last; ++step) {
      current_step_ = step;
      StepRecord record = coupled.solve_step(step, step * case_.run.delta_t);
      // No watchpoints: an empty interface.
      record.watchpoints = case_.watchpoints.sample(coupled.x(), coupled.y()).data();
      for (RunOutput* output : opened_) output->write_step(record);
      iterations_ += record.iterations;
      algorithm_time_ += record.coupler_time;
      // The last step is saved once, after the loop.
      if (case_.state_interval > 0 && step < last && step % case_.state_interval == 0)
        save_state(step);
    }
    save_state(last);
    current_step_ = 0;
  }

  /// The case's outputs, then the progress lines and the summary (the last: it records every
  /// other output's failure to close); a restarted run's continue after its step.
  void open_outputs() {
    const CoupledSolver& coupled = *case_.coupled_solver;
    if (!case_.watchpoints.empty()) case_.watchpoints.attach(coupled.x(), coupled.y());
    const RunDescription run = describe_run(case_);
    const OutputStart start{case_.files,
                            run,
                            coupled.x(),
                            coupled.y(),
                            case_.watchpoints.layout(),
                            case_.restart ? case_.restart->step : -1};
    std::vector<RunOutput*> outputs;
    for (const auto& output : case_.outputs) outputs.push_back(output.get());
    outputs.push_back(&progress_);
    outputs.push_back(&summary_);
    for (RunOutput* output : outputs) {
      output->open(start);
      opened_.push_back(output);
    }
    std::vector<RunOutput*> iterations;
    for (RunOutput* output : opened_)
      if (output->wants_iterations()) iterations.push_back(output);
    if (!iterations.empty())
      case_.coupled_solver->set_iteration_observer([iterations](const IterationReport& report) {
        for (RunOutput* output : iterations) output->write_iteration(report);
      });
  }

  /// Every step computed: completed, or stalled if some were accepted at the iteration limit
  /// with the residual above the solvers' noise. Steps at the limit at the noise are said.
  RunOutcome went_through() const {
    RunOutcome outcome;
    const std::size_t unconverged = summary().unconverged_steps().size();
    const std::size_t at_noise = summary().steps_at_noise().size();
    const std::string noise = at_noise == 0
                                  ? ""
                                  : fmt::format(
                                        "{} step{} at the iteration limit with the residual at the "
                                        "solvers' noise",
                                        at_noise, at_noise == 1 ? "" : "s");
    if (unconverged == at_noise) {
      outcome.reason = noise;
      return outcome;
    }
    outcome.status = RunStatus::kStalled;
    outcome.reason = fmt::format("{} of {} steps at the iteration limit{}", unconverged - at_noise,
                                 summary().steps_completed(),
                                 noise.empty() ? "" : " above the solvers' noise, " + noise);
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
            : (summary().steps_completed() > 0 ? "after the last step" : "at start-up");
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

  /// Between steps only: in the middle of a step the models hold half a step's columns.
  void save_state(int step) {
    // A restart continues the outputs after the state's step: they must hold it.
    for (RunOutput* output : opened_) output->flush();
    // The solvers first: a state file always has the solvers' restart data behind it.
    case_.coupled_solver->save_solver_restarts(step);
    SavedState saved;
    saved.step = step;
    saved.time = step * case_.run.delta_t;
    saved.coupled_solver = case_.coupled_solver->describe();
    case_.coupled_solver->save_state(saved.state);
    write_state_file(case_.files.state(), saved);
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

  /// Every output closed with how the run ended (in order: the summary, last, also records a
  /// failure of the others), then the run's last lines.
  void finish(RunOutcome& outcome) {
    const CoupledSolver& coupled = *case_.coupled_solver;
    RunEnd end;
    end.wall_time = std::chrono::duration<double>(Clock::now() - start_).count();
    const auto& solver_times = coupled.solver_time_total();
    end.solver_times = {solver_times[0], solver_times[1]};
    const double own_solvers = coupled.own_solvers_time_total();
    end.coupler_time = end.wall_time - coupled.solvers_wall_time_total() - own_solvers;
    end.unfinished_step = coupled.unfinished_step();
    end.unfinished_time = end.unfinished_step * case_.run.delta_t;
    end.unfinished_residuals = coupled.unfinished_residuals();
    // Not opened (the run stopped before its first step): the summary is written all the same.
    if (std::find(opened_.begin(), opened_.end(), &summary_) == opened_.end())
      opened_.push_back(&summary_);
    for (RunOutput* output : opened_) {
      end.outcome = outcome;
      // The summary, last, says how many steps the results file holds.
      if (output == &summary_)
        for (const RunOutput* other : opened_)
          if (other != &summary_ && other->steps_written())
            end.steps_written = other->steps_written();
      try {
        output->close(end);
      } catch (const std::exception& e) {
        note_write_failure(outcome, e);
      }
    }
    if (options_.silent) return;  // the caller reports the outcome
    print_report(outcome, end, own_solvers);
  }

  void print_report(const RunOutcome& outcome, const RunEnd& end, double own_solvers) const {
    const int steps = summary().steps_completed();
    // A results file that could not take every step says so beside the count.
    const std::string written =
        end.steps_written && *end.steps_written != steps
            ? fmt::format(" ({} of them in the results file)", *end.steps_written)
            : "";
    fmt::print("\n{} after {} time step{}{} in {:.3f} s{}\n", to_string(outcome.status), steps,
               steps == 1 ? "" : "s", written, end.wall_time,
               outcome.reason.empty() ? "" : ": " + outcome.reason);
    auto line = [](const std::string& label, const std::string& text) {
      fmt::print("  {:<18}: {}\n", label, text);
    };
    for (std::size_t i = 0; i < 2; ++i)
      line("solver " + case_.solvers[i]->name(), fmt::format("{:.3f} s", end.solver_times[i]));
    if (own_solvers > 0.0)
      line("surrogate", fmt::format("{:.3f} s (its solvers and coupling)", own_solvers));
    line("coupler",
         fmt::format("{:.3f} s ({:.1f} us per coupling iteration inside the steps)",
                     end.coupler_time, iterations_ ? 1e6 * algorithm_time_ / iterations_ : 0.0));
    if (steps > 0)
      line("iterations", fmt::format("{:.2f} per time step on average ({} in all)",
                                     double(iterations_) / steps, iterations_));
    for (const RunOutput* output : opened_)
      if (output != &summary_)
        for (const auto& [label, file] : output->files()) line(label, file.string());
    if (state_saved_) line("solver state", case_.files.state().string());
    line("summary", case_.files.summary().string());
    std::fflush(stdout);  // the error comes last, after the summary, also when piped
    if (!outcome.message.empty()) fmt::print(stderr, "\nerror: {}\n", outcome.message);
  }

  Case& case_;
  RunOptions options_;
  SummaryOutput summary_;
  ProgressOutput progress_;
  std::vector<RunOutput*> opened_;  ///< the outputs opened so far, the summary last
  Clock::time_point start_ = Clock::now();
  long iterations_ = 0;
  double algorithm_time_ = 0.0;
  bool state_saved_ = false;
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
    std::error_code error;
    std::filesystem::create_directories(c.files.directory, error);
    if (error)
      throw std::runtime_error(c.results_where + ": cannot create the directory " +
                               c.files.directory.string() + ": " + error.message());
    std::vector<std::filesystem::path> lock_files{c.files.lock()};
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
  Run run(c, options);
  report.outcome = run.execute();
  report.summary = run.summary();
  report.results_file = c.files.results();
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
