#include "coupler/outputs/progress_output.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>

namespace cocopp {

namespace {

/// "0.2 s", "4.7 s", "42 s", "3 min 20 s", "2 h 05 min": tenths below 10 s, so that a short
/// run does not say "0 s" left.
std::string duration(double seconds) {
  if (seconds < 9.95) return fmt::format("{:.1f} s", seconds);
  const long s = std::lround(seconds);
  if (s < 60) return fmt::format("{} s", s);
  if (s < 3600) return fmt::format("{} min {:02} s", s / 60, s % 60);
  return fmt::format("{} h {:02} min", s / 3600, (s % 3600) / 60);
}

}  // namespace

void ProgressOutput::open(const OutputStart& start) {
  first_ = start.run.timestep_start + 1;
  last_ = start.run.timestep_start + start.run.number_of_timesteps;
  summary_ = start.files.summary();
  start_ = std::chrono::steady_clock::now();
}

// The residual (2-norm, and as the criterion measures it where that differs: "relative
// 3.1e-07"), marked * at the iteration limit (~ there at the solvers' noise), the step's wall
// time, and the time left at the average pace of the steps so far.
void ProgressOutput::write_step(const StepRecord& r) {
  if (steps_) {
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start_;
    const double left = elapsed.count() / (r.step - first_ + 1) * (last_ - r.step);
    const std::string criterion =
        r.criterion_progress.empty() ? "" : " (" + r.criterion_progress + ")";
    const std::string surrogate = r.surrogate_iterations > 0
                                      ? fmt::format("  (surrogate {:>2})", r.surrogate_iterations)
                                      : "";
    const std::string time_left = r.step < last_ ? "  left " + duration(left) : "";
    fmt::print(
        "step {:>{}} / {}  t = {:<10.4g} iterations {:>3}  residual {:.3e}{}{}  {:8.3f} ms{}{}\n",
        r.step, std::to_string(last_).size(), last_, r.time, r.iterations, r.residual_norms.back(),
        r.converged ? " " : (r.at_noise ? "~" : "*"), criterion, 1e3 * r.wall_time, surrogate,
        time_left);
    std::fflush(stdout);
  }
  if (warnings_) print_warnings(r);
}

/// The first few steps' warnings as they come; all of them go to the summary.
void ProgressOutput::print_warnings(const StepRecord& record) {
  constexpr int kPrintedSteps = 5;
  if (record.warnings.empty() || ++steps_with_warnings_ > kPrintedSteps + 1) return;
  if (steps_with_warnings_ > kPrintedSteps) {
    fmt::print("warning: more steps with warnings follow: see \"warnings\" in {}\n",
               summary_.string());
    return;
  }
  for (const auto& warning : record.warnings)
    fmt::print("warning: step {}: {}\n", record.step, warning);
}

// Indented under the step's line to come.
void ProgressOutput::write_iteration(const IterationReport& r) {
  fmt::print("    step {} iteration {:>3}  residual {:.3e}{}  {:.3f} s into the step\n", r.step,
             r.iteration, r.residual, r.criterion.empty() ? "" : " (" + r.criterion + ")",
             r.step_seconds);
  std::fflush(stdout);
}

}  // namespace cocopp
