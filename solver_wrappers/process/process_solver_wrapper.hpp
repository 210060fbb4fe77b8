#pragma once
// ProcessSolverWrapper: a solver running as its own executable, driven over the cocopp solver
// protocol (docs/protocol.md). Case-file type `process`; the built-in tube solvers
// (`tube_flow`, `tube_structure`, `tube_ringmodel`) are the same class with a default command.
//
// Keys (docs/solver-wrappers.md): name, working_directory, command, transport, timeout,
// startup_timeout, log_file; and input_file for the built-in solvers. They are all read in
// the constructor, so that `cocopp check` validates them without starting anything.
//
// Every failure of the solver (crash, hang, error message, broken protocol) stops its process
// group, removes the channel and throws a SolverError that names the solver and quotes the end
// of its log. finalize() is safe to call at any time, more than once; the destructor calls it.
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/protocol/frame.hpp"
#include "core/protocol/messages.hpp"
#include "core/protocol/transport.hpp"
#include "solver_wrappers/solver_wrapper.hpp"

namespace cocopp {

class ChildProcess;

/// The command of a built-in solver: used when the case file gives no `command`.
struct DefaultCommand {
  std::filesystem::path executable;
  /// Default of the `input_file` key, relative to working_directory, passed as the only
  /// argument; empty: the solver has no input file and gets `arguments` instead.
  std::string input_file;
  std::vector<std::string> arguments;
  /// Variables the solver needs, added to its environment unless the coupler's sets them
  /// (whether or not the case file gives its own `command`).
  std::vector<std::pair<std::string, std::string>> environment;
  /// Arguments that make the executable read its input file (given after them) as a run would,
  /// report what it refuses and exit (the tube solvers' `--check`): `cocopp check` then finds a
  /// typo there, not `run`. Empty: the solver has no such check.
  std::vector<std::string> check_arguments;
  /// Default of `solver_busy_wait` (s): the built-in solvers answer within microseconds.
  double solver_busy_wait = 0.0;
};

class ProcessSolverWrapper : public SolverWrapper {
 public:
  ProcessSolverWrapper(const Settings& settings, const RunSettings& run,
                       std::optional<DefaultCommand> default_command = std::nullopt);
  ~ProcessSolverWrapper() override;
  ProcessSolverWrapper(const ProcessSolverWrapper&) = delete;
  ProcessSolverWrapper& operator=(const ProcessSolverWrapper&) = delete;

  const std::string& name() const override { return name_; }
  void set_default_name(const std::string& name) override;
  void check_solver_input() const override;
  std::string started() const override;
  std::string describe() const override;
  void check() const override;
  std::filesystem::path input_file() const override;

  void start() override;
  void initialize() override;
  const Interface& input_interface() const override { return input_interface_; }
  const Interface& output_interface() const override { return output_interface_; }
  void overlap_step_requests() override { overlap_step_requests_ = true; }
  void complete_step_requests() override { collect_replies(); }
  void initialize_step(int step, double time) override;
  const Interface& solve(const Interface& input) override;
  int substeps() const override { return substeps_; }
  Eigen::MatrixXd solve_substeps(const Eigen::MatrixXd& inputs) override;
  /// Sends REPORT_CONVERGENCE; a solver that cannot tell answers ERROR with the reason.
  void start_reporting_convergence() override;
  bool converged_at_first_iteration() const override { return converged_at_first_iteration_; }
  void finalize_step() override;
  void output_step() override;
  void save_restart(int step) override;
  void finalize() override;

  const std::vector<std::string>& command() const { return command_; }
  const std::filesystem::path& working_directory() const { return working_directory_; }
  const std::filesystem::path& log_file() const { return log_file_; }
  protocol::TransportKind transport() const { return transport_kind_; }
  /// The launched process (-1 before initialize()).
  int child_pid() const;
  /// The process talking to the coupler, from its HELLO (differs from child_pid under mpirun).
  std::int64_t solver_pid() const { return solver_pid_; }
  /// Variables the case's keys give the solver (set_case_environment).
  const std::vector<std::pair<std::string, std::string>>& case_environment() const {
    return case_environment_;
  }

 protected:
  /// Variables the case's own keys set (the openfoam wrapper's `sensitivity_probe`): given to
  /// the solver whatever the coupler's environment holds.
  void set_case_environment(std::vector<std::pair<std::string, std::string>> variables) {
    case_environment_ = std::move(variables);
  }

 private:
  enum class State { kNotStarted, kRunning, kStopped };

  void read_command(const Settings& settings, const std::optional<DefaultCommand>& default_command);
  /// transport: tcp's `host` and `port`, and `launcher` (docs/clusters.md).
  void read_tcp_keys(const Settings& settings);
  /// The peers the TCP channel refused while it waited for the solver, as warnings.
  void report_refused_peers() const;
  /// started_by: user: where the channel's address and token wait for the solver, mode 0600.
  std::filesystem::path channel_file() const;
  /// started_by: user: write the channel file and say where the coupler waits.
  void wait_for_user();
  void remove_channel_file() const noexcept;
  void launch();
  void wait_for_hello();
  void ensure_running() const;
  void build_interfaces(const sdk::InterfaceDescription& description);
  /// Send SOLVE and take its DATA (or DATA_CONVERGED, whose flag it keeps): the output values.
  std::vector<double> send_solve(const protocol::Frame& request);

  /// Send `request` (or, if null, only wait), check that the reply is `expected_reply` and
  /// return decode(reply). Every failure ends in fail().
  template <class Decode>
  auto call(const std::string& request_name, const protocol::Frame* request,
            protocol::MessageType expected_reply, double timeout_seconds, Decode&& decode);
  /// Wait for the reply to the request sent last, check it and return decode(reply).
  template <class Decode>
  auto receive_reply(const std::string& request_name, protocol::MessageType expected_reply,
                     double timeout_seconds, Decode&& decode);
  /// A step request whose OK is taken later (overlap_step_requests), or at once otherwise.
  void post(const std::string& request_name, const protocol::Frame& request);
  /// Send a request, after the replies still owed if the solver is gone (they say why).
  void send_request(const std::string& request_name, const protocol::Frame& request,
                    double timeout_seconds);
  /// Take the replies still owed to posted requests, in order; an error is named after its
  /// request and the step it was sent in.
  void collect_replies();
  /// Run one exchange with the solver, turning each way it can fail into a SolverError.
  template <class Exchange>
  auto guarded(const std::string& request_name, double timeout_seconds, Exchange&& exchange);
  protocol::AliveCheck alive_check();

  /// Stop the solver, remove the channel, throw SolverError(message).
  [[noreturn]] void fail(const std::string& message);
  [[noreturn]] void fail_with_log(const std::string& message);
  [[noreturn]] void fail_child_exited(const std::string& request_name);
  /// Stop the process group and remove the channel. Never throws.
  void release() noexcept;

  /// "step 3, iteration 2" (iteration for solve only); "" before the first step.
  std::string position(const std::string& request_name) const;
  /// "at step 3" / "before the first step".
  std::string at_position(const std::string& request_name) const;
  std::string log_tail() const;

  // From the case file.
  std::vector<std::string> check_arguments_;  ///< DefaultCommand::check_arguments
  std::string name_;
  bool name_given_ = false;      ///< `name` is in the case
  bool log_file_given_ = false;  ///< `log_file` is in the case
  std::filesystem::path working_directory_;
  std::vector<std::string> command_;
  std::string input_file_;  ///< known for built-in solvers only (checked by check())
  protocol::TransportKind transport_kind_ = protocol::TransportKind::kPipe;
  std::string tcp_host_;               ///< transport: tcp: the address the coupler listens on
  int tcp_port_ = 0;                   ///< and its port (0: any free one)
  std::vector<std::string> launcher_;  ///< put before the command: srun, mpirun, ssh, ...
  bool started_by_user_ = false;       ///< no child: the user starts the solver
  double timeout_ = 600.0;
  double startup_timeout_ = 60.0;
  std::chrono::microseconds busy_wait_{1000};  ///< of the pipe transport's receive
  double solver_busy_wait_ = 0.0;              ///< s, the solver's, through $COCOPP_BUSY_WAIT
  std::filesystem::path log_file_;
  std::vector<std::pair<std::string, std::string>> default_environment_;
  std::vector<std::pair<std::string, std::string>> case_environment_;
  // Where in the case file, for check() errors.
  std::string working_directory_where_;
  std::string log_file_where_;  ///< the case file's line of log_file (else of working_directory)
  std::string command_where_;
  std::string input_file_where_;
  RunSettings run_;

  // While running.
  State state_ = State::kNotStarted;
  bool initialized_ = false;  ///< it said HELLO and gave its interfaces
  std::unique_ptr<protocol::Transport> channel_;
  std::unique_ptr<ChildProcess> child_;
  std::int64_t solver_pid_ = -1;
  int step_ = 0;
  bool step_started_ = false;
  int iteration_ = 0;
  int substeps_ = 1;  ///< the solver's steps per coupling time step
  bool overlap_step_requests_ = false;
  struct PostedRequest {
    std::string name;
    int step;
  };
  std::deque<PostedRequest> posted_;  ///< sent, their OK not yet read
  bool reporting_convergence_ = false;
  bool converged_at_first_iteration_ = false;
  Interface input_interface_;
  Interface output_interface_;
};

/// The directory of the built-in solver executables: $COCOPP_BIN_DIR if set, else the
/// directory of the running executable.
std::filesystem::path builtin_solver_directory();

}  // namespace cocopp
