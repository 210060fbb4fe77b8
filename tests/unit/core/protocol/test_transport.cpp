#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "core/protocol/file_transport.hpp"
#include "core/protocol/messages.hpp"
#include "core/protocol/pipe_transport.hpp"
#include "core/protocol/transport.hpp"
#include "tests/support/temporary_directory.hpp"

namespace cocopp::protocol {
namespace {

using cocopp::testing::TemporaryDirectory;
using cocopp::testing::write_text;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Solver side of the echo tests: answer each SOLVE with DATA of the same values, STOP with OK.
void echo_until_stop(Transport& channel) {
  for (;;) {
    const Frame request = channel.receive(10.0, nullptr);
    if (message_type(request) == MessageType::kStop) {
      channel.send(encode_empty(MessageType::kOk));
      return;
    }
    channel.send(encode_data(decode_solve(request)));
  }
}

std::vector<double> ramp(std::size_t count) {
  std::vector<double> values(count);
  for (std::size_t i = 0; i < count; ++i) values[i] = 0.5 * static_cast<double>(i) - 3.0;
  return values;
}

class TransportTest : public ::testing::TestWithParam<TransportKind> {
 protected:
  TemporaryDirectory channel_directory_;
};

TEST_P(TransportTest, RoundTripBetweenThreads) {
  auto coupler = create_coupler_channel(GetParam(), channel_directory_.path());
  std::thread solver([&] {
    auto channel = open_solver_channel(GetParam(), channel_directory_.path(), 10.0, nullptr);
    echo_until_stop(*channel);
  });
  coupler->connect(10.0, nullptr);
  for (std::size_t count : {0, 1, 300, 100000}) {
    const auto values = ramp(count);
    coupler->send(encode_solve(values.data(), values.size()), 10.0, nullptr);
    EXPECT_EQ(decode_data(coupler->receive(10.0, nullptr)), values);
  }
  coupler->send(encode_empty(MessageType::kStop), 10.0, nullptr);
  decode_empty(coupler->receive(10.0, nullptr), MessageType::kOk);
  solver.join();
}

// 16 MB does not fit in a pipe buffer: exercises partial writes and reads.
TEST_P(TransportTest, LargeFramesCrossWhole) {
  auto coupler = create_coupler_channel(GetParam(), channel_directory_.path());
  std::thread solver([&] {
    auto channel = open_solver_channel(GetParam(), channel_directory_.path(), 10.0, nullptr);
    echo_until_stop(*channel);
  });
  coupler->connect(10.0, nullptr);
  const auto values = ramp(2'000'000);
  coupler->send(encode_solve(values.data(), values.size()), 30.0, nullptr);
  EXPECT_EQ(decode_data(coupler->receive(30.0, nullptr)), values);
  coupler->send(encode_empty(MessageType::kStop), 10.0, nullptr);
  coupler->receive(10.0, nullptr);
  solver.join();
}

TEST_P(TransportTest, RoundTripWithAForkedSolver) {
  auto coupler = create_coupler_channel(GetParam(), channel_directory_.path());
  const pid_t pid = ::fork();
  if (pid == 0) {
    int code = 0;
    try {
      auto channel = open_solver_channel(GetParam(), channel_directory_.path(), 10.0, nullptr);
      echo_until_stop(*channel);
    } catch (...) {
      code = 1;
    }
    ::_exit(code);
  }
  ASSERT_GT(pid, 0);
  coupler->connect(10.0, nullptr);
  const auto values = ramp(300);
  for (int i = 0; i < 20; ++i) {
    coupler->send(encode_solve(values.data(), values.size()), 10.0, nullptr);
    EXPECT_EQ(decode_data(coupler->receive(10.0, nullptr)), values);
  }
  coupler->send(encode_empty(MessageType::kStop), 10.0, nullptr);
  coupler->receive(10.0, nullptr);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

TEST_P(TransportTest, ReceiveTimesOutAndChecksTheSolverMeanwhile) {
  auto coupler = create_coupler_channel(GetParam(), channel_directory_.path());
  auto solver = open_solver_channel(GetParam(), channel_directory_.path(), 10.0, nullptr);
  coupler->connect(10.0, nullptr);
  int checks = 0;
  const auto start = Clock::now();
  EXPECT_THROW(coupler->receive(0.3, [&] { ++checks; }), TransportTimeout);
  const double elapsed = seconds_since(start);
  EXPECT_GE(elapsed, 0.29);
  EXPECT_LT(elapsed, 1.5);
  EXPECT_GE(checks, 2);  // at least every 100 ms
}

TEST_P(TransportTest, AnExceptionFromTheAliveCheckAbortsTheWait) {
  auto coupler = create_coupler_channel(GetParam(), channel_directory_.path());
  auto solver = open_solver_channel(GetParam(), channel_directory_.path(), 10.0, nullptr);
  coupler->connect(10.0, nullptr);
  struct SolverDied {};
  const auto start = Clock::now();
  EXPECT_THROW(coupler->receive(kWaitForever, [] { throw SolverDied(); }), SolverDied);
  EXPECT_LT(seconds_since(start), 1.0);
}

TEST_P(TransportTest, ChannelFilesAreRemovedWithTheCouplerEnd) {
  {
    auto coupler = create_coupler_channel(GetParam(), channel_directory_.path());
    auto solver = open_solver_channel(GetParam(), channel_directory_.path(), 10.0, nullptr);
    coupler->connect(10.0, nullptr);
    coupler->send(encode_empty(MessageType::kStop));  // left unread on purpose
    solver->send(encode_empty(MessageType::kOk));
  }
  EXPECT_TRUE(std::filesystem::is_empty(channel_directory_.path()));
}

INSTANTIATE_TEST_SUITE_P(Kinds, TransportTest,
                         ::testing::Values(TransportKind::kPipe, TransportKind::kFile),
                         [](const auto& info) { return transport_name(info.param); });

TEST(PipeTransportTest, ConnectTimesOutWhenNoSolverOpensThePipe) {
  TemporaryDirectory directory;
  auto coupler = create_coupler_channel(TransportKind::kPipe, directory.path());
  int checks = 0;
  const auto start = Clock::now();
  EXPECT_THROW(coupler->connect(0.3, [&] { ++checks; }), TransportTimeout);
  EXPECT_LT(seconds_since(start), 1.5);
  EXPECT_GE(checks, 2);
}

TEST(PipeTransportTest, ReceiveReportsASolverThatClosedThePipe) {
  TemporaryDirectory directory;
  auto coupler = create_coupler_channel(TransportKind::kPipe, directory.path());
  auto solver = open_solver_channel(TransportKind::kPipe, directory.path(), 10.0, nullptr);
  coupler->connect(10.0, nullptr);
  solver.reset();
  EXPECT_THROW(coupler->receive(5.0, nullptr), PeerClosed);
  EXPECT_THROW(coupler->send(encode_empty(MessageType::kStop), 5.0, nullptr), PeerClosed);
}

TEST(PipeTransportTest, SolverReportsACouplerThatClosedThePipe) {
  TemporaryDirectory directory;
  auto coupler = create_coupler_channel(TransportKind::kPipe, directory.path());
  auto solver = open_solver_channel(TransportKind::kPipe, directory.path(), 10.0, nullptr);
  coupler->connect(10.0, nullptr);
  coupler.reset();
  EXPECT_THROW(solver->receive(kWaitForever, nullptr), PeerClosed);
}

TEST(PipeTransportTest, CouplerFifosAreCreatedAndSolverWithoutThemFailsClearly) {
  TemporaryDirectory directory;
  try {
    open_solver_channel(TransportKind::kPipe, directory.path(), 1.0, nullptr);
    FAIL() << "no exception";
  } catch (const TransportError& e) {
    EXPECT_NE(std::string(e.what()).find(PipeTransport::kToSolverFifo), std::string::npos)
        << e.what();
  }
  auto coupler = create_coupler_channel(TransportKind::kPipe, directory.path());
  EXPECT_TRUE(std::filesystem::is_fifo(directory / PipeTransport::kToSolverFifo));
  EXPECT_TRUE(std::filesystem::is_fifo(directory / PipeTransport::kFromSolverFifo));
}

TEST(FileTransportTest, MessagesAreNumberedFilesAndStaleOnesAreRemoved) {
  TemporaryDirectory directory;
  EXPECT_EQ(FileTransport::message_file_name("to_solver_", 12), "to_solver_00000012.msg");
  write_text(directory / "from_solver_00000001.msg", "stale reply of an earlier run");
  write_text(directory / "solver.log", "not ours");
  auto coupler = create_coupler_channel(TransportKind::kFile, directory.path());
  EXPECT_FALSE(std::filesystem::exists(directory / "from_solver_00000001.msg"));
  EXPECT_TRUE(std::filesystem::exists(directory / "solver.log"));
  coupler->send(encode_empty(MessageType::kStop));
  EXPECT_TRUE(std::filesystem::exists(directory / "to_solver_00000001.msg"));
  auto solver = open_solver_channel(TransportKind::kFile, directory.path(), 1.0, nullptr);
  EXPECT_EQ(message_type(solver->receive(1.0, nullptr)), MessageType::kStop);
  EXPECT_FALSE(std::filesystem::exists(directory / "to_solver_00000001.msg"));
}

TEST(FileTransportTest, ATruncatedMessageFileIsAProtocolError) {
  TemporaryDirectory directory;
  auto coupler = create_coupler_channel(TransportKind::kFile, directory.path());
  write_text(directory / "from_solver_00000001.msg", std::string("\x09\0\0\0\x83", 5));
  EXPECT_THROW(coupler->receive(1.0, nullptr), ProtocolError);
}

}  // namespace
}  // namespace cocopp::protocol

namespace cocopp::protocol {
namespace {

// The coupler's busy wait (it reads without sleeping for a while before it polls): a reply
// that comes within it and one that comes long after it both arrive whole and in order.
TEST(PipeTransportTest, BusyWaitingReceiveGetsRepliesWithinAndAfterTheBusyWait) {
  TemporaryDirectory directory;
  auto coupler = create_coupler_channel(TransportKind::kPipe, directory.path(),
                                        std::chrono::microseconds(200));
  std::thread solver([&] {
    auto channel = open_solver_channel(TransportKind::kPipe, directory.path(), 10.0, nullptr);
    channel->send(encode_data(ramp(3)));                         // at once
    std::this_thread::sleep_for(std::chrono::milliseconds(30));  // long after the busy wait
    channel->send(encode_data(ramp(100000)));                    // more than a pipe holds
  });
  coupler->connect(10.0, nullptr);
  EXPECT_EQ(decode_data(coupler->receive(10.0, nullptr)), ramp(3));
  EXPECT_EQ(decode_data(coupler->receive(10.0, nullptr)), ramp(100000));
  solver.join();
}

// A solver that goes away while the coupler busy-waits is reported as such, at once.
TEST(PipeTransportTest, BusyWaitingReceiveReportsASolverThatClosedThePipe) {
  TemporaryDirectory directory;
  auto coupler = create_coupler_channel(TransportKind::kPipe, directory.path(),
                                        std::chrono::microseconds(100000));
  auto solver = open_solver_channel(TransportKind::kPipe, directory.path(), 10.0, nullptr);
  coupler->connect(10.0, nullptr);
  solver->send(encode_data(ramp(3)), 10.0, nullptr);
  EXPECT_EQ(decode_data(coupler->receive(10.0, nullptr)), ramp(3));
  solver.reset();
  EXPECT_THROW(coupler->receive(5.0, nullptr), PeerClosed);
}

}  // namespace
}  // namespace cocopp::protocol
