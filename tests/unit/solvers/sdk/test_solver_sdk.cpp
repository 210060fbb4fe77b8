// serve() against a coupler played by the test: a forked child serves a Solver, the test
// sends requests over the real transport and looks at the replies and the exit code.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <functional>
#include <memory>

#include "core/protocol/messages.hpp"
#include "core/protocol/transport.hpp"
#include "solvers/sdk/solver_sdk.hpp"
#include "tests/support/temporary_directory.hpp"

namespace cocopp::protocol {
namespace {

using cocopp::testing::read_text;
using cocopp::testing::TemporaryDirectory;

/// Two points, input displacement (6 values), output pressure (2 values) by default.
class ScriptedSolver : public sdk::Solver {
 public:
  sdk::InterfaceDescription initialize(const sdk::RunInfo&) override {
    sdk::ModelPart wall{"wall", {1, 2}, {0, 0, 0, 1, 0, 0}, {"displacement"}, {output_variable}};
    return {{wall}, {}};
  }
  void initialize_step(std::int32_t, double) override {
    if (throw_in_initialize_step) throw std::runtime_error("mesh became inverted");
  }
  std::vector<double> solve(const std::vector<double>& input) override {
    return std::vector<double>(output_size, input.empty() ? 0.0 : input[0]);
  }
  void finalize_step() override {}
  void finalize() override { std::fputs("finalized\n", stderr); }

  std::string output_variable = "pressure";
  std::size_t output_size = 2;
  bool throw_in_initialize_step = false;
};

/// A served solver in a forked child, and the coupler's end of its channel.
class ServedSolver {
 public:
  ServedSolver(const TemporaryDirectory& directory, std::function<void(ScriptedSolver&)> setup)
      : log_(directory / "solver.log") {
    channel_ = create_coupler_channel(TransportKind::kPipe, directory.path());
    pid_ = ::fork();
    if (pid_ == 0) {
      const int log = ::open(log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(log, STDERR_FILENO);
      ::setenv(kTransportVariable, "pipe", 1);
      ::setenv(kChannelVariable, directory.path().c_str(), 1);
      ScriptedSolver solver;
      setup(solver);
      char name[] = "scripted";
      char* argv[] = {name, nullptr};
      ::_exit(sdk::serve(solver, 1, argv));
    }
    channel_->connect(10.0, nullptr);
    hello_ = decode_hello(channel_->receive(10.0, nullptr));
  }
  ~ServedSolver() {
    channel_.reset();
    if (exit_code_ < 0) exit_code();
  }

  Frame request(const Frame& frame) {
    channel_->send(frame, 10.0, nullptr);
    return channel_->receive(10.0, nullptr);
  }
  Frame initialize() { return request(encode_initialize({0.1, 0})); }
  void close_channel() { channel_.reset(); }
  int exit_code() {
    int status = 0;
    ::waitpid(pid_, &status, 0);
    exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return exit_code_;
  }
  const Hello& hello() const { return hello_; }
  std::string log() const { return read_text(log_); }

 private:
  std::filesystem::path log_;
  std::unique_ptr<Transport> channel_;
  pid_t pid_ = -1;
  Hello hello_;
  int exit_code_ = -1;
};

TEST(SdkTest, ServesAFullRunAndStopsWithZero) {
  TemporaryDirectory directory;
  ServedSolver solver(directory, [](ScriptedSolver&) {});
  EXPECT_EQ(solver.hello().version, kProtocolVersion);
  EXPECT_GT(solver.hello().pid, 0);
  const auto description = decode_interface(solver.initialize());
  ASSERT_EQ(description.model_parts.size(), 1u);
  EXPECT_EQ(description.model_parts[0].name, "wall");
  decode_empty(solver.request(encode_initialize_step({1, 0.1})), MessageType::kOk);
  const std::vector<double> input = {7, 0, 0, 0, 0, 0};
  EXPECT_EQ(decode_data(solver.request(encode_solve(input.data(), input.size()))),
            (std::vector<double>{7, 7}));
  decode_empty(solver.request(encode_empty(MessageType::kFinalizeStep)), MessageType::kOk);
  decode_empty(solver.request(encode_empty(MessageType::kOutputStep)), MessageType::kOk);
  decode_empty(solver.request(encode_empty(MessageType::kStop)), MessageType::kOk);
  EXPECT_EQ(solver.exit_code(), 0);
  EXPECT_EQ(solver.log(), "finalized\n");
}

TEST(SdkTest, AnExceptionBecomesAnErrorReplyAndExitCodeOne) {
  TemporaryDirectory directory;
  ServedSolver solver(directory, [](ScriptedSolver& s) { s.throw_in_initialize_step = true; });
  solver.initialize();
  EXPECT_EQ(decode_error(solver.request(encode_initialize_step({1, 0.1}))), "mesh became inverted");
  EXPECT_EQ(solver.exit_code(), 1);
  EXPECT_NE(solver.log().find("mesh became inverted"), std::string::npos);
}

TEST(SdkTest, AWrongNumberOfSolveValuesIsReported) {
  TemporaryDirectory directory;
  ServedSolver solver(directory, [](ScriptedSolver& s) { s.output_size = 3; });
  solver.initialize();
  solver.request(encode_initialize_step({1, 0.1}));
  const std::vector<double> input(6, 0.0);
  EXPECT_EQ(decode_error(solver.request(encode_solve(input.data(), input.size()))),
            "solve() returned 3 values; the interface description implies 2");
  EXPECT_EQ(solver.exit_code(), 1);
}

TEST(SdkTest, AWrongNumberOfInputValuesIsReported) {
  TemporaryDirectory directory;
  ServedSolver solver(directory, [](ScriptedSolver&) {});
  solver.initialize();
  const std::vector<double> input(5, 0.0);
  EXPECT_EQ(decode_error(solver.request(encode_solve(input.data(), input.size()))),
            "SOLVE carried 5 values; the interface takes 6");
}

TEST(SdkTest, AnInvalidDescriptionIsReported) {
  TemporaryDirectory directory;
  ServedSolver solver(directory, [](ScriptedSolver& s) { s.output_variable = "presure"; });
  EXPECT_EQ(decode_error(solver.initialize()),
            "model part 'wall': unknown interface variable 'presure'");
}

TEST(SdkTest, RequestsBeforeInitializeAreRejectedButStopIsNot) {
  TemporaryDirectory directory;
  {
    ServedSolver solver(directory, [](ScriptedSolver&) {});
    EXPECT_EQ(decode_error(solver.request(encode_empty(MessageType::kFinalizeStep))),
              "FINALIZE_STEP before INITIALIZE");
    EXPECT_EQ(solver.exit_code(), 1);
  }
  ServedSolver solver(directory, [](ScriptedSolver&) {});
  decode_empty(solver.request(encode_empty(MessageType::kStop)), MessageType::kOk);
  EXPECT_EQ(solver.exit_code(), 0);
  EXPECT_EQ(solver.log(), "");  // finalize() is not called for a solver never initialized
}

TEST(SdkTest, ExitsWithOneWhenTheCouplerGoesAway) {
  TemporaryDirectory directory;
  ServedSolver solver(directory, [](ScriptedSolver&) {});
  solver.initialize();
  solver.close_channel();
  EXPECT_EQ(solver.exit_code(), 1);
  EXPECT_NE(solver.log().find("lost the connection to the coupler"), std::string::npos)
      << solver.log();
}

}  // namespace
}  // namespace cocopp::protocol
