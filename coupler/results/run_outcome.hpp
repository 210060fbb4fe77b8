#pragma once
// How a run ended, as one type for the results file, the summary, the printed messages and
// cocopp bench: no caller sorts outcomes by searching message text.
#include <stdexcept>
#include <string>

namespace cocopp {

enum class RunStatus {
  kCompleted,     ///< every time step, each converged
  kStalled,       ///< every time step, some accepted at the iteration limit
  kDiverged,      ///< stopped: non-finite values or a growing residual (DivergenceKind)
  kSolverFailed,  ///< stopped: a solver crashed, hung, or reported an error
  kInterrupted,   ///< stopped by a signal (Ctrl-C, kill)
  kFailed,        ///< stopped by any other error (e.g. writing the results)
  kInvalidCase,   ///< never started: the case file or a solver's set-up is invalid
};

enum class DivergenceKind { kNone, kNonFinite, kGrowth };

/// The coupling diverged (residual growth or non-finite data) in a step and iteration; the
/// message says where and what to change.
class DivergenceError : public std::runtime_error {
 public:
  DivergenceError(DivergenceKind kind, int step, int iteration, const std::string& message)
      : std::runtime_error(message), kind(kind), step(step), iteration(iteration) {}
  DivergenceKind kind;
  int step;
  int iteration;
};

/// "completed", "stalled", "diverged", "solver_failed", "interrupted", "failed", "invalid_case":
/// the `status` of the results file and of the summary.
const char* to_string(RunStatus status);
/// "", "non-finite values", "residual growth".
const char* to_string(DivergenceKind kind);
/// Throws std::invalid_argument for a name that is none of to_string's.
RunStatus run_status_from_string(const std::string& name);

/// Whether the run went through all its time steps (completed or stalled).
inline bool ran_all_steps(RunStatus status) {
  return status == RunStatus::kCompleted || status == RunStatus::kStalled;
}

struct RunOutcome {
  RunStatus status = RunStatus::kCompleted;
  DivergenceKind divergence = DivergenceKind::kNone;
  int step = 0;         ///< the time step the run stopped in (0: it did not stop in a step)
  int iteration = 0;    ///< the coupling iteration it stopped in (0: not known or none)
  std::string reason;   ///< short, e.g. "residual growth in step 3, iteration 7"
  std::string message;  ///< the whole error message, empty when the run went through

  /// The process exit code of `cocopp run`: 0 completed, 1 stopped, 2 invalid case, 3 stalled
  /// (every step computed, some accepted at the iteration limit above the solvers' noise).
  int exit_code() const;
};

}  // namespace cocopp
