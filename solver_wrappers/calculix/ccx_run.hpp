#pragma once
// One run of ccx (`ccx -i <job>`) as a child process (ChildProcess: own process group, output
// in a log file, stopped when the coupler stops), with a timeout, and a failure explained:
// exit code 201 after "increment size smaller than minimum" is non-convergence; *ERROR lines
// are a rejected deck (quoted); anything else (a crash, another exit code) quotes the log tail.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace cocopp::calculix {

struct CcxRunOptions {
  std::filesystem::path executable;
  std::filesystem::path working_directory;
  std::string job;  ///< reads <job>.inp
  std::filesystem::path log_file;
  int threads = 1;
  double timeout = 600.0;  ///< seconds
  /// Set for ccx besides its threads' (ccx_thread_environment).
  std::vector<std::pair<std::string, std::string>> environment{};
};

struct CcxRunResult {
  enum class Status { kSuccess, kNotConverged, kDeckError, kFailed, kTimedOut };
  Status status = Status::kSuccess;
  int exit_code = -1;
  std::string exit_description;  ///< "exited with code 201", "killed by signal 11 (...)"
  /// For kNotConverged and kFailed: the log's last lines; for kDeckError: ccx's *ERROR
  /// messages.
  std::string details;
  double seconds = 0.0;  ///< wall-clock time of the run
};

/// The environment that gives ccx `threads` threads: its equation solver (SPOOLES/PaStiX) and
/// its element loops read these; its libraries get one (python/cocopp/calculix.py's
/// ccx_environment is the same for the Python tools that run ccx).
std::vector<std::pair<std::string, std::string>> ccx_thread_environment(int threads);

/// Run ccx and wait for it; never throws for a failure of ccx itself (see the status), but
/// throws std::runtime_error if it cannot be started.
CcxRunResult run_ccx(const CcxRunOptions& options);

/// What this ccx's restart files keep beyond Debian's ccx 2.20: cocopp's patches
/// (scripts/calculix/, built by scripts/install-calculix.sh) add both.
struct CcxRestartSupport {
  /// The material state variables (plastic strain, back stress): plastic models restart
  /// exactly. Debian's ccx drops them without mortar contact.
  bool state_variables = false;
  /// The axisymmetry flag: CAX models restart at all. Debian's ccx crashes on them.
  bool axisymmetry = false;
  /// Not a restart's: a run's Newton iterations may start from a solution another run
  /// recorded (07-warm-start.patch, COCOPP_CCX_GUESS_IN/OUT).
  bool warm_start = false;
};

/// Asks `ccx -v` in `scratch_directory` (its log goes there); none if ccx cannot be run.
CcxRestartSupport restart_support(const std::filesystem::path& executable,
                                  const std::filesystem::path& scratch_directory);

/// Whether ccx's log says it gave up a step for want of convergence: an increment fell below the
/// minimum, it was cut back more often than its controls allow, or the step needed more
/// increments than *STEP, INC=.
bool gave_up(const std::string& log_text);

/// ccx's *ERROR messages in a log: each from its "*ERROR" line to the next blank line.
std::string error_messages(const std::string& log_text);

}  // namespace cocopp::calculix
