#pragma once
// A solver process started by the coupler. Each child runs in its own process group (so that
// stopping it also stops whatever it started, e.g. mpirun's ranks), with stdout and stderr
// appended to a log file, and dies with the coupler: PR_SET_PDEATHSIG covers a coupler killed
// by SIGKILL, kill_all_children() a coupler stopped by SIGINT/SIGTERM. PR_SET_PDEATHSIG fires
// when the *thread* that started the child ends: start children from the main thread (or one
// that lives as long as they should).
#include <sys/types.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace cocopp {

struct ChildOptions {
  /// argv; argv[0] is looked up with find_executable().
  std::vector<std::string> command;
  std::filesystem::path working_directory;
  /// Added to (or replacing values of) the coupler's environment.
  std::vector<std::pair<std::string, std::string>> environment;
  /// Receives stdout and stderr (appended).
  std::filesystem::path log_file;
  /// Empty the log file first.
  bool truncate_log = true;
};

class ChildProcess {
 public:
  /// Start the process; throws std::runtime_error naming the executable if it cannot start.
  explicit ChildProcess(const ChildOptions& options);
  /// Stops the process (and its group) if it still runs.
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  /// Whether the process still runs; reaps it (and remembers its status) once it has exited.
  bool running();
  /// Wait up to `timeout_seconds` for the process to exit; true if it has.
  bool wait_for_exit(double timeout_seconds);
  /// "exited with code 3", "killed by signal 11 (Segmentation fault)", or "is running".
  std::string describe_exit() const;
  /// Exit code if the process exited normally, -1 otherwise (running, killed).
  int exit_code() const;
  /// SIGTERM to the process group, up to `grace_seconds` to exit, then SIGKILL.
  void stop(double grace_seconds);

 private:
  void on_reaped(int status);

  pid_t pid_ = -1;    ///< also the process group id
  int exit_fd_ = -1;  ///< pidfd of the child: readable once it has exited
  bool reaped_ = false;
  bool status_known_ = false;
  int status_ = 0;
};

/// The executable `command` names: a path with a slash is taken relative to
/// `working_directory`; a bare name is looked up in `working_directory`, then on PATH.
/// Throws std::runtime_error naming it if it is missing or not executable.
std::filesystem::path find_executable(const std::string& command,
                                      const std::filesystem::path& working_directory);

/// SIGKILL to the process group of every live child. Async-signal-safe (it only calls kill()):
/// meant for the coupler's SIGINT/SIGTERM handler.
void kill_all_children() noexcept;

/// A short command run to its end (a version query, an input check): whether it ended within
/// the time given (else it was stopped), how, and everything it printed.
struct CommandOutput {
  bool finished = false;
  int exit_code = -1;            ///< ChildProcess::exit_code()
  std::string exit_description;  ///< ChildProcess::describe_exit()
  std::string output;            ///< stdout and stderr
};

/// Runs `options.command` to its end, at most `timeout_seconds`, with its output in
/// `options.log_file`, which is read into the result and removed. Throws std::runtime_error if
/// the command cannot start.
CommandOutput run_to_end(const ChildOptions& options, double timeout_seconds);

/// The last `count` lines of a text file ("" if it is missing or empty).
std::string read_last_lines(const std::filesystem::path& file, std::size_t count);

}  // namespace cocopp
