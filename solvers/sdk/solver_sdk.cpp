#include "solvers/sdk/solver_sdk.hpp"

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <memory>
#include <set>
#include <stdexcept>

#include "core/protocol/messages.hpp"
#include "core/protocol/transport.hpp"
#include "core/protocol/variable_components.hpp"

namespace cocopp::sdk {

namespace {

namespace protocol = cocopp::protocol;
using protocol::Frame;
using protocol::MessageType;

/// How long a solver waits for the coupler to open its end of the channel.
constexpr double kConnectTimeoutSeconds = 60.0;

void print_help(const std::string& program) {
  std::cout << program
            << " is a cocopp solver: the cocopp coupler starts it and drives it time step by\n"
               "time step. Run it through `cocopp run case.yaml`, with a solver of this type in\n"
               "the case file. The coupler passes the channel to talk through in the environment\n"
               "variables COCOPP_TRANSPORT and COCOPP_CHANNEL (see docs/protocol.md).\n";
}

/// Number of values `variables` take on `part` (points x components, summed).
std::size_t data_size(const ModelPart& part, const std::vector<std::string>& variables) {
  std::size_t size = 0;
  for (const auto& variable : variables) {
    const int components = protocol::variable_components(variable);
    if (components == 0)
      throw std::runtime_error("model part '" + part.name + "': unknown interface variable '" +
                               variable + "'");
    size += part.ids.size() * static_cast<std::size_t>(components);
  }
  return size;
}

/// Answers the coupler's requests with the Solver's methods.
class Server {
 public:
  Server(Solver& solver, protocol::Transport& channel, pid_t coupler_pid)
      : solver_(solver), channel_(channel), coupler_pid_(coupler_pid) {}

  int run() {
    try {
      channel_.send(protocol::encode_hello({protocol::kProtocolVersion, ::getpid()}));
      while (handle(channel_.receive(protocol::kWaitForever, [this] { check_coupler(); }))) {
      }
      return 0;
    } catch (const protocol::TransportError& e) {
      // The channel is gone: nobody to report to but the log.
      std::cerr << "cocopp solver: lost the connection to the coupler: " << e.what() << "\n";
      return 1;
    } catch (const std::exception& e) {
      return report_error(e.what());
    } catch (...) {
      return report_error("unknown exception");
    }
  }

 private:
  int report_error(const std::string& message) {
    std::cerr << "cocopp solver: error: " << message << "\n";
    try {
      channel_.send(protocol::encode_error(message));
    } catch (const std::exception& e) {
      std::cerr << "cocopp solver: could not send the error to the coupler: " << e.what() << "\n";
    }
    return 1;
  }

  // With the file transport there is no end-of-file to notice; a new parent means the
  // coupler has gone.
  void check_coupler() const {
    if (coupler_pid_ != 0 && ::getppid() != coupler_pid_)
      throw protocol::PeerClosed("the coupler has exited");
  }

  /// Handle one request; false after STOP.
  bool handle(const Frame& request) {
    const MessageType type = protocol::message_type(request);
    if (type == MessageType::kStop && !initialized_) {
      reply_ok();  // stopped before it started: nothing to finalize
      return false;
    }
    if (type == MessageType::kSubsteps) return on_substeps(protocol::decode_substeps(request));
    if (type != MessageType::kInitialize && !initialized_)
      throw protocol::ProtocolError(protocol::message_name(type) + " before INITIALIZE");
    switch (type) {
      case MessageType::kInitialize:
        on_initialize(protocol::decode_initialize(request));
        return true;
      case MessageType::kInitializeStep: {
        const auto step = protocol::decode_initialize_step(request);
        if (substeps_ == 1) {
          solver_.initialize_step(step.step, step.time);
        } else {  // the window's substeps start with its first SOLVE
          window_ = step;
          window_solves_ = 0;
          solver_.save_state();
        }
        return reply_ok();
      }
      case MessageType::kSolve:
        if (substeps_ == 1)
          on_solve(protocol::decode_solve(request));
        else
          on_solve_window(protocol::decode_solve(request));
        return true;
      case MessageType::kFinalizeStep:
        protocol::decode_empty(request, type);
        solver_.finalize_step();
        return reply_ok();
      case MessageType::kOutputStep:
        protocol::decode_empty(request, type);
        solver_.output_step();
        return reply_ok();
      case MessageType::kSaveRestart: {
        const std::int32_t step = protocol::decode_save_restart(request);
        if (solver_.can_restart()) solver_.save_restart(step * substeps_);
        return reply_ok();
      }
      case MessageType::kReportConvergence:
        protocol::decode_empty(request, type);
        solver_.start_reporting_convergence();
        reporting_convergence_ = true;
        return reply_ok();
      case MessageType::kStop:
        protocol::decode_empty(request, type);
        solver_.finalize();
        reply_ok();
        return false;
      default:
        throw protocol::ProtocolError("unexpected request " + protocol::message_name(type));
    }
  }

  bool reply_ok() {
    channel_.send(protocol::encode_empty(MessageType::kOk));
    return true;
  }

  bool on_substeps(std::uint32_t substeps) {
    if (initialized_) throw protocol::ProtocolError("SUBSTEPS after INITIALIZE");
    if (substeps > 1 && !solver_.can_substep())
      throw std::runtime_error(
          "the case asks this solver for " + std::to_string(substeps) +
          " substeps per coupling time step, but it cannot take substeps: it keeps no state in "
          "memory to go back to at each coupling iteration (Solver::can_substep, save_state, "
          "restore_state; docs/protocol.md)");
    substeps_ = static_cast<std::int32_t>(substeps);
    return reply_ok();
  }

  void on_initialize(RunInfo run) {
    if (initialized_) throw protocol::ProtocolError("INITIALIZE received twice");
    window_delta_t_ = run.delta_t;
    run.delta_t /= substeps_;  // the solver's own time step
    run.timestep_start *= substeps_;
    if (run.timestep_start > 0 && !solver_.can_restart())
      throw std::runtime_error(
          "the coupler restarts the run after time step " + std::to_string(run.timestep_start) +
          ", but this solver cannot restart (it saves no restart data): run the case from the "
          "start");
    InterfaceDescription description = solver_.initialize(run);
    validate(description);
    initialized_ = true;
    channel_.send(protocol::encode_interface(description));
  }

  void on_solve(const std::vector<double>& input) {
    if (input.size() != input_size_)
      throw protocol::ProtocolError("SOLVE carried " + std::to_string(input.size()) +
                                    " values; the interface takes " + std::to_string(input_size_));
    std::vector<double> output;
    try {
      output = solver_.solve(input);
    } catch (const InputRejected& e) {
      std::cerr << "cocopp solver: input rejected: " << e.what() << "\n";
      channel_.send(protocol::encode_rejected(e.what()));
      return;
    }
    check_output_size(output);
    send_output(output, solver_.converged_at_first_iteration());
  }

  void check_output_size(const std::vector<double>& output) const {
    if (output.size() != output_size_)
      throw std::runtime_error("solve() returned " + std::to_string(output.size()) +
                               " values; the interface description implies " +
                               std::to_string(output_size_));
  }

  /// DATA, or DATA_CONVERGED after REPORT_CONVERGENCE.
  void send_output(const std::vector<double>& output, bool converged) {
    channel_.send(reporting_convergence_ ? protocol::encode_data_converged(output, converged)
                                         : protocol::encode_data(output));
  }

  /// SOLVE of a window of substeps: from the window's start, each substep with its input;
  /// DATA holds the outputs of all, in order.
  void on_solve_window(const std::vector<double>& input) {
    const auto k = static_cast<std::size_t>(substeps_);
    if (input.size() != k * input_size_)
      throw protocol::ProtocolError("SOLVE carried " + std::to_string(input.size()) +
                                    " values; a window of " + std::to_string(k) +
                                    " substeps takes " + std::to_string(k * input_size_));
    if (window_solves_++ > 0) solver_.restore_state();
    std::vector<double> output;
    output.reserve(k * output_size_);
    bool converged = true;
    for (std::int32_t j = 1; j <= substeps_; ++j) {
      const std::int32_t step = (window_.step - 1) * substeps_ + j;
      // (the window's end less the substeps still to come: the last is the window's time)
      const double time = window_.time - (substeps_ - j) * (window_delta_t_ / substeps_);
      solver_.initialize_step(step, time);
      const auto from = input.begin() + static_cast<std::ptrdiff_t>((j - 1) * input_size_);
      std::vector<double> substep_output;
      try {
        substep_output = solver_.solve(
            std::vector<double>(from, from + static_cast<std::ptrdiff_t>(input_size_)));
      } catch (const InputRejected& e) {
        solver_.restore_state();  // the window's start, as a rejection promises
        std::cerr << "cocopp solver: input rejected in substep " << j << ": " << e.what() << "\n";
        channel_.send(protocol::encode_rejected(e.what()));
        return;
      }
      check_output_size(substep_output);
      output.insert(output.end(), substep_output.begin(), substep_output.end());
      converged = converged && solver_.converged_at_first_iteration();
      if (j < substeps_) solver_.finalize_substep();
    }
    send_output(output, converged);
  }

  // Errors in the description are the solver's: report them here, where they are made.
  void validate(const InterfaceDescription& description) {
    std::set<std::string> names;
    input_size_ = output_size_ = 0;
    for (const auto& part : description.model_parts) {
      if (part.name.empty()) throw std::runtime_error("a model part has no name");
      if (!names.insert(part.name).second)
        throw std::runtime_error("model part '" + part.name + "' is described twice");
      if (part.coordinates.size() != 3 * part.ids.size())
        throw std::runtime_error(
            "model part '" + part.name + "' has " + std::to_string(part.ids.size()) + " ids but " +
            std::to_string(part.coordinates.size()) + " coordinates (3 per point expected)");
      input_size_ += data_size(part, part.input_variables);
      output_size_ += data_size(part, part.output_variables);
    }
    if (!description.initial_output.empty() && description.initial_output.size() != output_size_)
      throw std::runtime_error("initial_output has " +
                               std::to_string(description.initial_output.size()) +
                               " values; the output interface has " + std::to_string(output_size_) +
                               " (or leave it empty for zeros)");
  }

  Solver& solver_;
  protocol::Transport& channel_;
  pid_t coupler_pid_;
  bool initialized_ = false;
  bool reporting_convergence_ = false;
  std::int32_t substeps_ = 1;    ///< per coupling time step (SUBSTEPS)
  double window_delta_t_ = 0.0;  ///< the coupling time step
  protocol::StepInfo window_;    ///< the window being solved (its end)
  int window_solves_ = 0;        ///< SOLVEs of it so far
  std::size_t input_size_ = 0;
  std::size_t output_size_ = 0;
};

}  // namespace

bool wants_help(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) return true;
  return false;
}

int serve(Solver& solver, int argc, char** argv) {
  const std::string program = argc > 0 ? argv[0] : "this solver";
  if (wants_help(argc, argv)) {
    print_help(program);
    return 0;
  }
  if (!protocol::channel_in_environment()) {
    std::cerr << program
              << ": this program is a cocopp solver; run it through `cocopp run case.yaml` "
                 "(COCOPP_TRANSPORT and COCOPP_CHANNEL are not set)\n";
    return 2;
  }
  pid_t coupler_pid = ::getppid();
  std::unique_ptr<protocol::Transport> link;
  try {
    const protocol::ChannelAddress address = protocol::channel_from_environment();
    // Over TCP the connection tells when the coupler has gone; the parent may be a shell or a
    // batch script that the user started the solver from (started_by: user), not the coupler.
    if (address.kind == protocol::TransportKind::kTcp) coupler_pid = 0;
    link = protocol::open_solver_channel(
        address, kConnectTimeoutSeconds,
        [coupler_pid] {
          if (coupler_pid != 0 && ::getppid() != coupler_pid)
            throw protocol::PeerClosed("the coupler has exited");
        },
        protocol::busy_wait_from_environment());
  } catch (const std::exception& e) {
    std::cerr << program << ": cannot connect to the cocopp coupler: " << e.what() << "\n";
    return 1;
  }
  return Server(solver, *link, coupler_pid).run();
}

}  // namespace cocopp::sdk
