#include "solver_wrappers/process/process_solver_wrapper.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>

#include "core/case/path_problem.hpp"
#include "core/case/suggest.hpp"
#include "core/protocol/tcp_transport.hpp"
#include "solver_wrappers/process/child_process.hpp"
#include "solver_wrappers/process/python_hint.hpp"
#include "solver_wrappers/solver_error.hpp"

namespace cocopp {

COCOPP_REGISTER(SolverWrapperRegistry, "process", ProcessSolverWrapper)

namespace {

using protocol::Frame;
using protocol::MessageType;

constexpr std::size_t kLogTailLines = 20;
/// After SIGTERM, before SIGKILL.
constexpr double kStopGraceSeconds = 2.0;
/// STOP gets at most this long (or `timeout`, if shorter): finalize() must not hang a run.
constexpr double kStopTimeoutSeconds = 30.0;
/// A solver exits by itself after answering STOP, or after sending ERROR; it gets this long
/// before it is stopped (so that its exit status and last output are known).
constexpr double kExitAfterStopSeconds = 10.0;
constexpr double kExitAfterErrorSeconds = 2.0;

/// Thrown by the alive check when the solver process has ended.
struct ChildExited : std::exception {};
/// The solver answered with ERROR.
struct ReportedError : std::exception {
  explicit ReportedError(std::string text) : text(std::move(text)) {}
  std::string text;
};

/// The solver answered SOLVE with REJECTED: it serves on from the step's start.
struct RejectedInput : std::exception {
  explicit RejectedInput(std::string text) : text(std::move(text)) {}
  std::string text;
};

auto decode_ok = [](const Frame& frame) { protocol::decode_empty(frame, MessageType::kOk); };

}  // namespace

void ProcessSolverWrapper::ensure_running() const {
  if (state_ == State::kRunning) return;
  throw SolverError(name_,
                    "solver '" + name_ + "' is not running (" +
                        (state_ == State::kNotStarted ? "initialize() was not called)"
                                                      : "it was stopped, or failed earlier)"));
}

protocol::AliveCheck ProcessSolverWrapper::alive_check() {
  return [this] {
    if (child_ && !child_->running()) throw ChildExited();
  };
}

// The templates come first: their return types are deduced, so they must precede their uses.
template <class Exchange>
auto ProcessSolverWrapper::guarded(const std::string& request_name, double timeout_seconds,
                                   Exchange&& exchange) {
  ensure_running();
  try {
    return exchange();
  } catch (const RejectedInput& rejection) {
    throw SolverRejectedInput(
        name_, fmt::format("solver '{}' rejected the input {}: {}\n(log: {})", name_,
                           at_position(request_name), rejection.text, log_file_.string()));
  } catch (const ReportedError& error) {
    if (child_) child_->wait_for_exit(kExitAfterErrorSeconds);
    fail(fmt::format("solver '{}' reported an error: {}\n(during {} {}; log: {})", name_,
                     error.text, request_name, at_position(request_name), log_file_.string()));
  } catch (const ChildExited&) {
    fail_child_exited(request_name);
  } catch (const protocol::TransportTimeout&) {
    const std::string what =
        request_name == "startup" ? "did not connect" : "did not answer " + request_name;
    const std::string where = position(request_name);
    if (started_by_user_)
      fail(fmt::format("solver '{}' (started by the user) {} within {} ({}){}", name_, what,
                       protocol::seconds_text(timeout_seconds),
                       where.empty() ? "before the first step" : where,
                       request_name == "startup"
                           ? fmt::format(": start it with {}={} in its environment",
                                         protocol::kChannelFileVariable, channel_file().string())
                           : ""));
    fail_with_log(fmt::format("solver '{}' {} within {} ({}); its log {} ends with:", name_, what,
                              protocol::seconds_text(timeout_seconds),
                              where.empty() ? "before the first step" : where, log_file_.string()));
  } catch (const protocol::PeerClosed&) {
    if (started_by_user_)
      fail(fmt::format("solver '{}' (started by the user) closed the connection during {} {}",
                       name_, request_name, at_position(request_name)));
    // A crashing solver closes the pipe before the alive check sees that it has died.
    child_->wait_for_exit(kExitAfterErrorSeconds);
    if (!child_->running()) fail_child_exited(request_name);
    fail_with_log(fmt::format(
        "solver '{}' (pid {}) closed the pipe during {} {}; its log {} ends with:", name_,
        child_->pid(), request_name, at_position(request_name), log_file_.string()));
  } catch (const protocol::ProtocolError& e) {
    fail_with_log(
        fmt::format("solver '{}' broke the protocol during {} {}: {}; its log {} ends with:", name_,
                    request_name, at_position(request_name), e.what(), log_file_.string()));
  } catch (const protocol::TransportError& e) {
    fail(fmt::format("solver '{}': communication failed during {} {}: {}", name_, request_name,
                     at_position(request_name), e.what()));
  }
}

template <class Decode>
auto ProcessSolverWrapper::receive_reply(const std::string& request_name,
                                         MessageType expected_reply, double timeout_seconds,
                                         Decode&& decode) {
  return guarded(request_name, timeout_seconds, [&] {
    const Frame reply = channel_->receive(timeout_seconds, alive_check());
    const MessageType type = protocol::message_type(reply);
    if (type == MessageType::kError)
      throw ReportedError(protocol::printable_text(protocol::decode_error(reply)));
    if (type == MessageType::kRejected &&
        (expected_reply == MessageType::kData || expected_reply == MessageType::kDataConverged))
      throw RejectedInput(protocol::printable_text(protocol::decode_rejected(reply)));
    if (type != expected_reply)
      throw protocol::ProtocolError("answered " + request_name + " with " +
                                    protocol::message_name(type) + " instead of " +
                                    protocol::message_name(expected_reply));
    return decode(reply);
  });
}

template <class Decode>
auto ProcessSolverWrapper::call(const std::string& request_name, const Frame* request,
                                MessageType expected_reply, double timeout_seconds,
                                Decode&& decode) {
  if (request != nullptr) send_request(request_name, *request, timeout_seconds);
  collect_replies();  // the solver answers in order: the posted requests' replies come first
  return receive_reply(request_name, expected_reply, timeout_seconds, decode);
}

void ProcessSolverWrapper::send_request(const std::string& request_name, const Frame& request,
                                        double timeout_seconds) {
  if (!posted_.empty()) {
    try {
      channel_->send(request, timeout_seconds, alive_check());
      return;
    } catch (const ChildExited&) {
    } catch (const protocol::PeerClosed&) {
    }
    // The solver stopped after an earlier request: its reply says why (an ERROR is still in the
    // pipe after the process has gone). If all were OK, the send below fails as it did.
    collect_replies();
  }
  guarded(request_name, timeout_seconds,
          [&] { channel_->send(request, timeout_seconds, alive_check()); });
}

void ProcessSolverWrapper::post(const std::string& request_name, const Frame& request) {
  if (!overlap_step_requests_) {
    call(request_name, &request, MessageType::kOk, timeout_, decode_ok);
    return;
  }
  send_request(request_name, request, timeout_);
  posted_.push_back({request_name, step_});
}

void ProcessSolverWrapper::collect_replies() {
  const int step = step_;
  while (!posted_.empty()) {
    const PostedRequest posted = posted_.front();
    posted_.pop_front();
    step_ = posted.step;  // so that an error names the step the request was sent in
    receive_reply(posted.name, MessageType::kOk, timeout_, decode_ok);
  }
  step_ = step;
}

ProcessSolverWrapper::ProcessSolverWrapper(const Settings& settings, const RunSettings& run,
                                           std::optional<DefaultCommand> default_command)
    : run_(run) {
  name_ = settings.get_name("name", settings.required<std::string>("type"));
  name_given_ = settings.has("name");
  log_file_given_ = settings.has("log_file");
  const std::filesystem::path directory = settings.required<std::string>("working_directory");
  working_directory_ = std::filesystem::absolute(run.case_directory / directory).lexically_normal();
  working_directory_where_ = settings.where("working_directory");
  // A solver the user starts (a batch script's srun, another terminal): no command, and the
  // coupler waits for it on TCP (docs/clusters.md).
  started_by_user_ = settings.get_choice("started_by", "coupler", {"coupler", "user"}) == "user";
  if (started_by_user_) {
    for (const char* key : {"command", "input_file", "launcher"})
      if (settings.has(key))
        settings.fail(key,
                      "the coupler starts nothing for a solver with started_by: user: "
                      "remove it");
  } else {
    read_command(settings, default_command);
  }
  if (default_command) default_environment_ = default_command->environment;
  // The built-in check reads the default input file format: not with a command of the user's.
  if (default_command && !settings.has("command"))
    check_arguments_ = default_command->check_arguments;
  transport_kind_ = protocol::parse_transport_kind(
      settings.get_choice("transport", "pipe", {"pipe", "file", "tcp"}));
  read_tcp_keys(settings);
  if (started_by_user_ && transport_kind_ != protocol::TransportKind::kTcp)
    settings.fail("started_by",
                  "a solver the user starts connects over TCP: add transport: tcp "
                  "(and host: an address of this machine it reaches)");
  timeout_ = settings.get_in_range("timeout", 600.0, Range::timeout());  // seconds
  startup_timeout_ = settings.get_in_range("startup_timeout", 60.0, Range::timeout());
  // Reading the reply pipe without sleeping saves a process wake-up per message on fast solvers
  // (docs/benchmarks.md); on slow ones it costs at most this much CPU per message.
  busy_wait_ = std::chrono::microseconds(
      std::llround(1e6 * settings.get_in_range("busy_wait", 1e-3, Range::closed(0.0, 0.1))));
  // The solver's side of the same (SDK solvers, pipe transport): worth it where the machine has
  // a core for the waiting solver or the solvers are fast (docs/solver-wrappers.md).
  solver_busy_wait_ = settings.get_in_range(
      "solver_busy_wait", default_command ? default_command->solver_busy_wait : 0.0,
      Range::closed(0.0, 0.1));
  log_file_ = working_directory_ / settings.get<std::string>("log_file", name_ + ".log");
  log_file_where_ =
      settings.has("log_file") ? settings.where("log_file") : working_directory_where_;
  // Steps of its own per coupling time step (docs/coupling.md, "Substeps").
  substeps_ = settings.get_int_in_range("substeps", 1, 1, 10000);
}

void ProcessSolverWrapper::read_tcp_keys(const Settings& settings) {
  if (transport_kind_ != protocol::TransportKind::kTcp) {
    for (const char* key : {"host", "port"})
      if (settings.has(key))
        settings.fail(key, "is a key of transport: tcp (this solver uses " +
                               protocol::transport_name(transport_kind_) + ")");
  }
  // Loopback unless the case names an interface: a solver on another host needs it to.
  tcp_host_ = settings.get<std::string>("host", "127.0.0.1");
  if (tcp_host_.empty() || tcp_host_.find_first_of(" \t/") != std::string::npos)
    settings.fail("host", "give an address or a name of this machine, e.g. 10.0.0.1");
  tcp_port_ = settings.get_int_in_range("port", 0, 0, 65535);
  launcher_ = settings.get<std::vector<std::string>>("launcher", {});
  if (settings.has("launcher") && (launcher_.empty() || launcher_[0].empty()))
    settings.fail("launcher",
                  "give the command that starts the solver elsewhere, e.g. "
                  "[srun, --nodes=1, --ntasks=1, --nodelist=node2]");
}

void ProcessSolverWrapper::read_command(const Settings& settings,
                                        const std::optional<DefaultCommand>& default_command) {
  if (default_command && default_command->input_file.empty() && !settings.has("command")) {
    command_ = {default_command->executable.string()};
    command_.insert(command_.end(), default_command->arguments.begin(),
                    default_command->arguments.end());
    command_where_ = settings.where();
    return;
  }
  if (default_command && !settings.has("command")) {
    input_file_ = settings.get<std::string>("input_file", default_command->input_file);
    input_file_where_ = settings.where("input_file");
    command_ = {default_command->executable.string(), input_file_};
    command_where_ = settings.where();
    return;
  }
  if (default_command && !default_command->input_file.empty() && settings.has("input_file"))
    settings.fail("input_file", "give either 'command' or 'input_file', not both");
  command_ = settings.required<std::vector<std::string>>("command");
  if (command_.empty() || command_[0].empty())
    settings.fail("command",
                  "must start with the executable to run, e.g. [./my_solver, input.txt]");
  command_where_ = settings.where("command");
}

ProcessSolverWrapper::~ProcessSolverWrapper() {
  try {
    finalize();
  } catch (...) {
    // Unwinding from another error, most likely: that one is the one to report.
  }
}

void ProcessSolverWrapper::set_default_name(const std::string& name) {
  if (name_given_) return;
  name_ = name;
  if (!log_file_given_) log_file_ = working_directory_ / (name_ + ".log");
}

std::string ProcessSolverWrapper::describe() const {
  if (started_by_user_)
    return fmt::format("{}: started by the user (in {}; {} transport)", name_,
                       working_directory_.string(), protocol::transport_name(transport_kind_));
  return fmt::format("{}: {}{} (in {}; log {}; {} transport{})", name_,
                     launcher_.empty() ? "" : join(launcher_, " ") + " ", join(command_, " "),
                     working_directory_.string(), log_file_.string(),
                     protocol::transport_name(transport_kind_),
                     substeps_ > 1 ? fmt::format("; {} substeps a time step", substeps_) : "");
}

std::string ProcessSolverWrapper::started() const {
  if (started_by_user_) return name_ + " (started by the user)";
  return child_ ? fmt::format("{} (pid {})", name_, child_->pid()) : name_;
}

void ProcessSolverWrapper::check() const {
  const std::string solver = "solver '" + name_ + "': ";
  if (const auto why = path_problem(working_directory_, PathKind::kDirectory); !why.empty())
    throw CaseError(working_directory_where_ + ": " + solver + "working directory " +
                    working_directory_.string() + " " + why);
  if (const auto why = creation_problem(log_file_.parent_path()); !why.empty())
    throw CaseError(log_file_where_ + ": " + solver + "the log file's folder " +
                    log_file_.parent_path().string() + " " + why);
  if (started_by_user_) return;  // no command: the user starts the solver
  try {
    find_executable(command_[0], working_directory_);
  } catch (const std::runtime_error& e) {
    throw CaseError(command_where_ + ": " + solver + e.what());
  }
  if (input_file_.empty()) return;
  const auto input = working_directory_ / input_file_;
  if (const auto why = path_problem(input, PathKind::kRegularFile); !why.empty())
    throw CaseError(input_file_where_ + ": " + solver + "input file " + input.string() + " " + why);
}

// The solver itself reads the file, in its working directory as a run starts it: the coupler
// never links a solver's code, and the message is the one the run would end with.
void ProcessSolverWrapper::check_solver_input() const {
  if (started_by_user_ || check_arguments_.empty() || input_file_.empty()) return;
  constexpr double kCheckTimeout = 60.0;  // s; reading an input file takes milliseconds
  ChildOptions options;
  options.command = {command_[0]};
  options.command.insert(options.command.end(), check_arguments_.begin(), check_arguments_.end());
  options.command.push_back(input_file_);
  options.working_directory = working_directory_;
  // Outside the working directory: `cocopp check` writes nothing into the case.
  options.log_file = std::filesystem::temp_directory_path() /
                     fmt::format("cocopp_check_{}_{}.log", ::getpid(), name_);
  const CommandOutput check = run_to_end(options, kCheckTimeout);
  if (check.finished && check.exit_code == 0) return;
  const std::string command = join(options.command, " ");
  if (!check.finished)
    throw CaseError(
        fmt::format("{}: solver '{}': `{}` did not finish within {:g} s and was stopped",
                    input_file_where_, name_, command, kCheckTimeout));
  std::string output = check.output;
  while (!output.empty() && std::isspace(static_cast<unsigned char>(output.back())))
    output.pop_back();
  throw CaseError(fmt::format("{}: solver '{}' refuses its input file (`{}` {}):\n{}",
                              input_file_where_, name_, command, check.exit_description, output));
}

std::filesystem::path ProcessSolverWrapper::input_file() const {
  return input_file_.empty() ? std::filesystem::path() : working_directory_ / input_file_;
}

int ProcessSolverWrapper::child_pid() const {
  return child_ ? child_->pid() : -1;
}

void ProcessSolverWrapper::start() {
  if (state_ != State::kNotStarted)
    throw std::logic_error("solver '" + name_ + "' is started twice");
  check();
  launch();
}

void ProcessSolverWrapper::initialize() {
  if (initialized_) throw std::logic_error("solver '" + name_ + "' is initialized twice");
  if (state_ == State::kNotStarted) start();
  wait_for_hello();
  if (substeps_ > 1) {  // before INITIALIZE: the solver's own time step depends on it
    const Frame substeps = protocol::encode_substeps(static_cast<std::uint32_t>(substeps_));
    call("substeps", &substeps, MessageType::kOk, timeout_, decode_ok);
  }
  const Frame request = protocol::encode_initialize({run_.delta_t, run_.timestep_start});
  build_interfaces(
      call("initialize", &request, MessageType::kInterface, timeout_, protocol::decode_interface));
  // From now on every reply is DATA of the output interface, OK, or a text: a longer frame
  // is a corrupt stream, refused before it is read.
  const auto data_frame =
      1 + 8 + 8 * static_cast<std::size_t>(output_interface_.size()) * std::size_t(substeps_);
  channel_->set_max_payload(std::max(data_frame, 1 + 4 + protocol::kMaxReceivedText));
  initialized_ = true;
}

void ProcessSolverWrapper::launch() {
  try {
    std::filesystem::create_directories(log_file_.parent_path());
    protocol::CouplerChannelOptions channel;
    channel.kind = transport_kind_;
    channel.directory = working_directory_;
    channel.busy_wait = busy_wait_;
    channel.host = tcp_host_;
    channel.port = tcp_port_;
    channel_ = protocol::create_coupler_channel(channel);
    if (started_by_user_) {
      wait_for_user();
      state_ = State::kRunning;
      return;
    }
    ChildOptions options;
    options.command = launcher_;
    options.command.insert(options.command.end(), command_.begin(), command_.end());
    options.working_directory = working_directory_;
    options.environment = protocol::solver_environment(channel_->address());
    if (solver_busy_wait_ > 0.0)
      options.environment.emplace_back(protocol::kBusyWaitVariable,
                                       fmt::format("{}", solver_busy_wait_));
    for (const auto& [variable, value] : default_environment_)
      if (std::getenv(variable.c_str()) == nullptr)
        options.environment.emplace_back(variable, value);
    options.environment.insert(options.environment.end(), case_environment_.begin(),
                               case_environment_.end());
    options.log_file = log_file_;
    options.truncate_log = true;
    child_ = std::make_unique<ChildProcess>(options);
  } catch (const std::exception& e) {
    release();
    throw SolverError(name_, "cannot start solver '" + name_ + "': " + e.what());
  }
  state_ = State::kRunning;
}

std::filesystem::path ProcessSolverWrapper::channel_file() const {
  return working_directory_ / ("cocopp_channel_" + name_ + ".env");
}

void ProcessSolverWrapper::wait_for_user() {
  protocol::write_channel_file(channel_file(), channel_->address(), name_);
  fmt::print(stderr,
             "solver '{}': waiting up to {} for it to connect to {}: start it with {}={} in "
             "its environment\n",
             name_, protocol::seconds_text(startup_timeout_), channel_->address().channel,
             protocol::kChannelFileVariable, channel_file().string());
}

void ProcessSolverWrapper::report_refused_peers() const {
  if (const auto* tcp = dynamic_cast<const protocol::TcpTransport*>(channel_.get()))
    for (const auto& peer : tcp->refused())
      fmt::print(stderr, "warning: solver '{}': refused a connection from {}\n", name_, peer);
}

void ProcessSolverWrapper::wait_for_hello() {
  // One deadline for both stages of the startup.
  const auto start = std::chrono::steady_clock::now();
  guarded("startup", startup_timeout_, [&] { channel_->connect(startup_timeout_, alive_check()); });
  if (started_by_user_) remove_channel_file();  // the secret is used: nobody else gets in
  report_refused_peers();
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  const auto hello =
      call("startup", nullptr, MessageType::kHello,
           std::max(startup_timeout_ - elapsed.count(), 0.0), protocol::decode_hello);
  solver_pid_ = hello.pid;
  if (hello.version != protocol::kProtocolVersion)
    fail(
        fmt::format("solver '{}' speaks protocol version {}, this cocopp speaks version {}: "
                    "rebuild the solver with this version's SDK",
                    name_, hello.version, protocol::kProtocolVersion));
}

void ProcessSolverWrapper::build_interfaces(const sdk::InterfaceDescription& description) {
  std::vector<Interface::Part> input_parts;
  std::vector<Interface::Part> output_parts;
  for (const auto& part : description.model_parts) {
    const auto points = static_cast<Eigen::Index>(part.ids.size());
    if (part.coordinates.size() != 3 * part.ids.size())
      fail(
          fmt::format("solver '{}' sent {} coordinates for the {} points of model part '{}' "
                      "(3 per point expected)",
                      name_, part.coordinates.size(), points, part.name));
    // One ModelPart shared by the input and the output interface.
    auto model_part = std::make_shared<ModelPart>();
    model_part->name = part.name;
    model_part->ids = part.ids;
    model_part->coordinates = Eigen::Map<const Coordinates>(part.coordinates.data(), points, 3);
    if (!part.input_variables.empty()) input_parts.push_back({model_part, part.input_variables});
    if (!part.output_variables.empty()) output_parts.push_back({model_part, part.output_variables});
  }
  try {
    input_interface_ = Interface(input_parts);
    output_interface_ = Interface(output_parts);
  } catch (const std::invalid_argument& e) {
    fail(fmt::format("solver '{}' described an invalid interface: {}", name_, e.what()));
  }
  const auto& initial = description.initial_output;
  if (initial.empty()) return;  // zeros
  if (static_cast<Eigen::Index>(initial.size()) != output_interface_.size())
    fail(
        fmt::format("solver '{}' sent {} initial output values for an output interface of {} "
                    "({})",
                    name_, initial.size(), output_interface_.size(), output_interface_.describe()));
  output_interface_.set_data(Eigen::Map<const Eigen::VectorXd>(initial.data(), initial.size()));
}

void ProcessSolverWrapper::initialize_step(int step, double time) {
  step_ = step;
  step_started_ = true;
  iteration_ = 0;
  const Frame request = protocol::encode_initialize_step({step, time});
  post("initialize_step", request);
}

const Interface& ProcessSolverWrapper::solve(const Interface& input) {
  if (substeps_ > 1)
    throw std::logic_error("solver '" + name_ + "' takes substeps: solve_substeps(), not solve()");
  if (!input.same_layout(input_interface_))
    throw std::invalid_argument(
        fmt::format("solver '{}': solve() was given {} but the solver's input interface is {}",
                    name_, input.describe(), input_interface_.describe()));
  ++iteration_;
  const Frame request = protocol::encode_solve(input.data().data(), input.size());
  const std::vector<double> output = send_solve(request);
  if (static_cast<Eigen::Index>(output.size()) != output_interface_.size())
    fail(
        fmt::format("solver '{}' returned {} values from solve {}; its output interface has {} "
                    "({})",
                    name_, output.size(), at_position("solve"), output_interface_.size(),
                    output_interface_.describe()));
  output_interface_.set_data(Eigen::Map<const Eigen::VectorXd>(output.data(), output.size()));
  return output_interface_;
}

std::vector<double> ProcessSolverWrapper::send_solve(const Frame& request) {
  if (!reporting_convergence_)
    return call("solve", &request, MessageType::kData, timeout_, protocol::decode_data);
  auto data = call("solve", &request, MessageType::kDataConverged, timeout_,
                   protocol::decode_data_converged);
  converged_at_first_iteration_ = data.converged;
  return std::move(data.values);
}

Eigen::MatrixXd ProcessSolverWrapper::solve_substeps(const Eigen::MatrixXd& inputs) {
  if (substeps_ == 1) return SolverWrapper::solve_substeps(inputs);
  if (inputs.rows() != input_interface_.size() || inputs.cols() != substeps_)
    throw std::invalid_argument(fmt::format(
        "solver '{}': solve_substeps() was given {} x {} values, the window takes {} x {}", name_,
        inputs.rows(), inputs.cols(), input_interface_.size(), substeps_));
  ++iteration_;
  // Column-major: one substep's input after the other, as SOLVE carries them.
  const Frame request = protocol::encode_solve(inputs.data(), std::size_t(inputs.size()));
  const std::vector<double> output = send_solve(request);
  const Eigen::Index rows = output_interface_.size();
  if (static_cast<Eigen::Index>(output.size()) != rows * substeps_)
    fail(
        fmt::format("solver '{}' returned {} values from solve {}; a window of {} substeps of "
                    "its output interface has {} ({} each)",
                    name_, output.size(), at_position("solve"), substeps_, rows * substeps_,
                    output_interface_.describe()));
  const Eigen::MatrixXd outputs = Eigen::Map<const Eigen::MatrixXd>(output.data(), rows, substeps_);
  output_interface_.set_data(outputs.col(substeps_ - 1));
  return outputs;
}

void ProcessSolverWrapper::start_reporting_convergence() {
  if (reporting_convergence_) return;  // two criteria may ask the same solver
  const Frame request = protocol::encode_empty(MessageType::kReportConvergence);
  call("report_convergence", &request, MessageType::kOk, timeout_, decode_ok);
  reporting_convergence_ = true;
}

void ProcessSolverWrapper::finalize_step() {
  const Frame request = protocol::encode_empty(MessageType::kFinalizeStep);
  post("finalize_step", request);
}

void ProcessSolverWrapper::output_step() {
  const Frame request = protocol::encode_empty(MessageType::kOutputStep);
  post("output_step", request);
}

void ProcessSolverWrapper::save_restart(int step) {
  const Frame request = protocol::encode_save_restart(step);
  call("save_restart", &request, MessageType::kOk, timeout_, decode_ok);
}

void ProcessSolverWrapper::finalize() {
  // Never started, started but never initialized (the other solver failed first: this one was
  // never connected), already finalized, or failed.
  if (state_ != State::kRunning || !initialized_) {
    release();
    return;
  }
  const Frame request = protocol::encode_empty(MessageType::kStop);
  call("stop", &request, MessageType::kOk, std::min(timeout_, kStopTimeoutSeconds), decode_ok);
  if (child_) child_->wait_for_exit(kExitAfterStopSeconds);
  release();
}

void ProcessSolverWrapper::fail(const std::string& message) {
  release();
  throw SolverError(name_, message);
}

void ProcessSolverWrapper::fail_with_log(const std::string& message) {
  release();  // first: the log is complete once the process has ended
  const std::string tail = log_tail();
  // A Python solver that died for want of a module: which interpreter ran, and what to change.
  std::string hint;
  try {
    hint = python_module_hint(command_, find_executable(command_.at(0), working_directory_), tail,
                              installed_python_sdk_directory());
  } catch (const std::exception&) {
    // no executable to name: no hint
  }
  throw SolverError(name_, message + "\n" + tail + (hint.empty() ? "" : "\n" + hint));
}

void ProcessSolverWrapper::fail_child_exited(const std::string& request_name) {
  fail_with_log(fmt::format("solver '{}' (pid {}) {} during {} {}; last lines of {}:", name_,
                            child_->pid(), child_->describe_exit(), request_name,
                            at_position(request_name), log_file_.string()));
}

void ProcessSolverWrapper::release() noexcept {
  state_ = State::kStopped;
  if (child_) child_->stop(kStopGraceSeconds);
  if (started_by_user_) remove_channel_file();
  channel_.reset();  // closes the channel and removes its FIFOs or message files
}

std::string ProcessSolverWrapper::position(const std::string& request_name) const {
  if (!step_started_) return "";
  std::string text = "step " + std::to_string(step_);
  if (request_name == "solve") text += ", iteration " + std::to_string(iteration_);
  return text;
}

std::string ProcessSolverWrapper::at_position(const std::string& request_name) const {
  const std::string where = position(request_name);
  return where.empty() ? "before the first step" : "at " + where;
}

void ProcessSolverWrapper::remove_channel_file() const noexcept {
  std::error_code ignored;
  std::filesystem::remove(channel_file(), ignored);
}

std::string ProcessSolverWrapper::log_tail() const {
  const std::string tail = read_last_lines(log_file_, kLogTailLines);
  return tail.empty() ? "(the log is empty)" : protocol::printable_text(tail, 16 * 1024);
}

}  // namespace cocopp
