#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <thread>
#include <vector>

#include "core/protocol/file_transport.hpp"
#include "core/protocol/messages.hpp"
#include "core/protocol/pipe_transport.hpp"
#include "core/protocol/tcp_transport.hpp"
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
    auto channel = open_solver_channel(coupler->address(), 10.0, nullptr);
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
    auto channel = open_solver_channel(coupler->address(), 10.0, nullptr);
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
      auto channel = open_solver_channel(coupler->address(), 10.0, nullptr);
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
  auto solver = open_solver_channel(coupler->address(), 10.0, nullptr);
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
  auto solver = open_solver_channel(coupler->address(), 10.0, nullptr);
  coupler->connect(10.0, nullptr);
  struct SolverDied {};
  const auto start = Clock::now();
  EXPECT_THROW(coupler->receive(kWaitForever, [] { throw SolverDied(); }), SolverDied);
  EXPECT_LT(seconds_since(start), 1.0);
}

TEST_P(TransportTest, ChannelFilesAreRemovedWithTheCouplerEnd) {
  {
    auto coupler = create_coupler_channel(GetParam(), channel_directory_.path());
    auto solver = open_solver_channel(coupler->address(), 10.0, nullptr);
    coupler->connect(10.0, nullptr);
    coupler->send(encode_empty(MessageType::kStop));  // left unread on purpose
    solver->send(encode_empty(MessageType::kOk));
  }
  EXPECT_TRUE(std::filesystem::is_empty(channel_directory_.path()));
}

INSTANTIATE_TEST_SUITE_P(Kinds, TransportTest,
                         ::testing::Values(TransportKind::kPipe, TransportKind::kFile,
                                           TransportKind::kTcp),
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

// Issue 17, defect 4: a length prefix above the channel's bound is refused at once, before a
// byte of payload is allocated or awaited; frames within it, also large ones, cross whole.
TEST_P(TransportTest, AFrameLongerThanTheBoundIsRefusedBeforeItIsRead) {
  auto coupler = create_coupler_channel(GetParam(), channel_directory_.path());
  auto solver = open_solver_channel(coupler->address(), 10.0, nullptr);
  coupler->connect(10.0, nullptr);
  const auto values = ramp(300000);  // 2.4 MB: more than one read chunk of the pipe
  coupler->set_max_payload(encode_data(values).size());
  std::thread sender([&] { solver->send(encode_data(values)); });  // more than a pipe holds
  EXPECT_EQ(decode_data(coupler->receive(10.0, nullptr)), values);
  sender.join();
  coupler->set_max_payload(100);
  solver->send(encode_data(ramp(12)));  // 105 bytes
  const auto start = Clock::now();
  try {
    coupler->receive(10.0, nullptr);
    FAIL() << "no exception";
  } catch (const ProtocolError& e) {
    EXPECT_NE(std::string(e.what()).find("105"), std::string::npos) << e.what();
  }
  EXPECT_LT(seconds_since(start), 1.0);
}

// A lying length prefix (1 GiB announced, nothing follows) with the default bound: the wait
// times out as for any missing message, and no gigabyte was allocated up front (the buffer
// grows with what arrives): the process's peak resident memory grows by far less.
TEST(PipeTransportTest, ALyingLengthPrefixCostsNoMemoryUpFront) {
  TemporaryDirectory directory;
  auto coupler = create_coupler_channel(TransportKind::kPipe, directory.path());
  // The solver's ends, opened by hand: its read end (for connect) and its write end.
  const int reader =
      ::open((directory / PipeTransport::kToSolverFifo).c_str(), O_RDONLY | O_NONBLOCK);
  const int fd = ::open((directory / PipeTransport::kFromSolverFifo).c_str(), O_WRONLY);
  ASSERT_GE(reader, 0);
  ASSERT_GE(fd, 0);
  coupler->connect(10.0, nullptr);
  const std::uint8_t prefix[4] = {0x00, 0x00, 0x00, 0x40};  // 2^30
  ASSERT_EQ(::write(fd, prefix, 4), 4);
  const auto peak_kib = [] {
    rusage usage{};
    ::getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss;
  };
  const long before = peak_kib();
  EXPECT_THROW(coupler->receive(0.3, nullptr), TransportTimeout);
  EXPECT_LT(peak_kib() - before, 64 * 1024) << "KiB of peak memory grown by the wait";
  ::close(fd);
  ::close(reader);
}

// Issue 17, defects 4, 5 and 10: a FIFO planted at a reply's name is an error, not a wait for
// ever; a reply file larger than the bound is refused unread; a link planted at a message's
// temporary name is replaced, its target untouched.
TEST(FileTransportTest, PlantedFifosHugeFilesAndLinksAreRefused) {
  TemporaryDirectory directory;
  auto coupler = create_coupler_channel(TransportKind::kFile, directory.path());
  const auto reply = directory / "from_solver_00000001.msg";
  ASSERT_EQ(::mkfifo(reply.c_str(), 0600), 0);
  const auto start = Clock::now();
  try {
    coupler->receive(5.0, nullptr);
    FAIL() << "no exception";
  } catch (const TransportError& e) {
    EXPECT_NE(std::string(e.what()).find("is not a regular file"), std::string::npos) << e.what();
  }
  EXPECT_LT(seconds_since(start), 1.0);
  std::filesystem::remove(reply);
  write_text(reply, std::string(2000, 'x'));
  coupler->set_max_payload(1000);
  try {
    coupler->receive(5.0, nullptr);
    FAIL() << "no exception";
  } catch (const ProtocolError& e) {
    EXPECT_NE(std::string(e.what()).find("holds a frame of 1996 bytes"), std::string::npos)
        << e.what();
  }
  const auto target = directory / "precious.txt";
  write_text(target, "keep me");
  std::filesystem::create_symlink(target, directory / "to_solver_00000001.tmp");
  coupler->send(encode_empty(MessageType::kStop));
  EXPECT_EQ(cocopp::testing::read_text(target), "keep me");
  EXPECT_TRUE(std::filesystem::is_regular_file(directory / "to_solver_00000001.msg"));
}

TEST(PrintableText, ControlCharactersAreReplacedAndLongTextsCut) {
  EXPECT_EQ(printable_text("line 1\n\tline 2"), "line 1\n\tline 2");
  EXPECT_EQ(printable_text("red \x1b[31m bell \x07 del \x7f"), "red ?[31m bell ? del ?");
  EXPECT_EQ(printable_text(std::string(5000, 'a'), 4096),
            std::string(4096, 'a') + "... [904 more bytes]");
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

// The solver's busy wait ($COCOPP_BUSY_WAIT, settings.solver_busy_wait): requests that come
// within it and long after it arrive whole and in order at a solver that reads without sleeping.
TEST(PipeTransportTest, BusyWaitingSolverGetsRequestsWithinAndAfterTheBusyWait) {
  TemporaryDirectory directory;
  auto coupler = create_coupler_channel(TransportKind::kPipe, directory.path());
  std::vector<double> received_first, received_second;
  std::thread solver([&] {
    auto channel = open_solver_channel(TransportKind::kPipe, directory.path(), 10.0, nullptr,
                                       std::chrono::microseconds(2000));
    received_first = decode_data(channel->receive(10.0, nullptr));
    received_second = decode_data(channel->receive(10.0, nullptr));
  });
  coupler->connect(10.0, nullptr);
  coupler->send(encode_data(ramp(3)), 10.0, nullptr);
  std::this_thread::sleep_for(std::chrono::milliseconds(30));  // long after the busy wait
  coupler->send(encode_data(ramp(100000)), 10.0, nullptr);     // more than a pipe holds
  solver.join();
  EXPECT_EQ(received_first, ramp(3));
  EXPECT_EQ(received_second, ramp(100000));
}

TEST(PipeTransportTest, TheSolversBusyWaitComesFromTheEnvironmentAndIsChecked) {
  const char* saved = std::getenv(kBusyWaitVariable);
  const std::string saved_value = saved != nullptr ? saved : "";
  ::unsetenv(kBusyWaitVariable);
  EXPECT_EQ(busy_wait_from_environment(), std::chrono::microseconds(0));
  ::setenv(kBusyWaitVariable, "0.001", 1);
  EXPECT_EQ(busy_wait_from_environment(), std::chrono::microseconds(1000));
  for (const char* bad : {"fast", "0.5", "-1", "1e-3s"}) {
    ::setenv(kBusyWaitVariable, bad, 1);
    try {
      busy_wait_from_environment();
      ADD_FAILURE() << bad << " was accepted";
    } catch (const TransportError& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("COCOPP_BUSY_WAIT='") + bad + "'"),
                std::string::npos)
          << e.what();
    }
  }
  if (saved != nullptr)
    ::setenv(kBusyWaitVariable, saved_value.c_str(), 1);
  else
    ::unsetenv(kBusyWaitVariable);
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

/// A raw TCP client of the coupler's port on loopback (a peer that is not a cocopp solver).
int raw_client(const ChannelAddress& address) {
  const auto [host, port] = split_host_port(address.channel);
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<std::uint16_t>(port));
  ::inet_pton(AF_INET, host.c_str(), &to.sin_addr);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&to), sizeof to) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

/// What the peer `fd` got until the coupler closed it (within 5 s).
std::string read_until_closed(int fd) {
  std::string got;
  char buffer[256];
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  timeval limit{5, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &limit, sizeof limit);
  for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0;) got.append(buffer, n);
  ::close(fd);
  return got;
}

// Issue 50: the coupler lets in only the peer that proves the run's token. A peer with a wrong
// one and a peer that says nothing are refused (and recorded), get not a byte, and do not keep
// the solver out; once the solver is in, the port is closed.
TEST(TcpTransportTest, OnlyThePeerWithTheTokenIsLetIn) {
  auto coupler = create_coupler_channel({TransportKind::kTcp, {}, {}, "127.0.0.1", 0});
  const ChannelAddress address = coupler->address();
  EXPECT_EQ(address.channel.rfind("127.0.0.1:", 0), 0u) << address.channel;
  EXPECT_EQ(address.token.size(), TcpTransport::kTokenCharacters);
  const int silent = raw_client(address);
  const int impostor = raw_client(address);
  ASSERT_GE(silent, 0);
  ASSERT_GE(impostor, 0);
  const int stranger = raw_client(address);
  ASSERT_GE(stranger, 0);
  std::string wrong = std::string(TcpTransport::kGreeting) + std::string(64, 'a') + "\n";
  ASSERT_EQ(::write(impostor, wrong.data(), wrong.size()), static_cast<ssize_t>(wrong.size()));
  const std::string http = "GET / HTTP/1.0\r\n\r\n";
  ASSERT_EQ(::write(stranger, http.data(), http.size()), static_cast<ssize_t>(http.size()));
  auto solver = open_solver_channel(address, 10.0, nullptr);
  const auto start = Clock::now();
  coupler->connect(10.0, nullptr);
  EXPECT_LT(seconds_since(start), 2.0);  // the silent peer did not hold the solver up
  solver->send(encode_empty(MessageType::kOk));
  decode_empty(coupler->receive(10.0, nullptr), MessageType::kOk);
  coupler->send(encode_empty(MessageType::kStop));
  EXPECT_EQ(message_type(solver->receive(10.0, nullptr)), MessageType::kStop);

  EXPECT_EQ(read_until_closed(impostor), "");
  EXPECT_EQ(read_until_closed(silent), "");
  EXPECT_EQ(read_until_closed(stranger), "");
  const auto& refused = dynamic_cast<const TcpTransport&>(*coupler).refused();
  ASSERT_EQ(refused.size(), 3u);
  const auto refused_for = [&](const std::string& why) {
    return std::count_if(refused.begin(), refused.end(), [&](const std::string& entry) {
      return entry.rfind("127.0.0.1:", 0) == 0 && entry.find(why) != std::string::npos;
    });
  };
  EXPECT_EQ(refused_for("a wrong token"), 1);
  EXPECT_EQ(refused_for("not a cocopp solver"), 1);
  EXPECT_EQ(refused_for("another peer proved the token first"), 1);
  EXPECT_EQ(raw_client(address), -1);  // a second client: nobody listens any more
}

TEST(TcpTransportTest, AWrongTokenIsToldOnTheSolversSideAndTheCouplerTimesOutNamingIt) {
  auto coupler = create_coupler_channel({TransportKind::kTcp, {}, {}, "127.0.0.1", 0});
  ChannelAddress address = coupler->address();
  address.token = std::string(64, '0');
  auto solver = open_solver_channel(address, 10.0, nullptr);
  try {
    coupler->connect(0.5, nullptr);
    FAIL() << "no exception";
  } catch (const TransportTimeout& e) {
    EXPECT_NE(std::string(e.what()).find("refused 127.0.0.1:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("a wrong token"), std::string::npos) << e.what();
  }
  try {
    solver->receive(5.0, nullptr);
    FAIL() << "no exception";
  } catch (const TransportError& e) {
    EXPECT_NE(std::string(e.what()).find("refused this solver (is COCOPP_TOKEN this run's"),
              std::string::npos)
        << e.what();
  }
  address.token = "short";
  EXPECT_THROW(open_solver_channel(address, 1.0, nullptr), TransportError);
}

TEST(TcpTransportTest, ASolverThatGoesAwayIsAClosedPeer) {
  auto coupler = create_coupler_channel({TransportKind::kTcp, {}, {}, "127.0.0.1", 0});
  auto solver = open_solver_channel(coupler->address(), 10.0, nullptr);
  coupler->connect(10.0, nullptr);
  solver.reset();
  EXPECT_THROW(coupler->receive(5.0, nullptr), PeerClosed);
}

TEST(TcpTransportTest, ChannelsAndAddressesAreCheckedWithWhatIsWrong) {
  EXPECT_EQ(split_host_port("10.0.0.2:40123"), std::make_pair(std::string("10.0.0.2"), 40123));
  EXPECT_EQ(split_host_port("[::1]:7"), std::make_pair(std::string("::1"), 7));
  for (const char* bad : {"10.0.0.2", ":80", "host:0", "host:99999", "host:8o"})
    EXPECT_THROW(split_host_port(bad), TransportError) << bad;
  try {
    create_coupler_channel({TransportKind::kTcp, {}, {}, "192.0.2.77", 0});
    FAIL() << "no exception";
  } catch (const TransportError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot listen on 192.0.2.77:0"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace cocopp::protocol
