// Round-trip latency of the solver protocol: the coupler side sends SOLVE with N doubles and
// waits for DATA, against a forked child that serves an echo solver through the SDK, exactly
// as a solver executable would. Measured for the pipe, the TCP (loopback) and the file transport,
// and, as the floor, a bare ping-pong of the same bytes through two anonymous pipes between the
// same two kinds of process (blocking reads and writes, no framing), in the same run.
//
//   bench_protocol_roundtrip [doubles=300] [round_trips=2000] [HOST SOLVER_NETNS]
//
// With HOST and SOLVER_NETNS (as root, bench/two_hosts.py) only the TCP transport is measured,
// the coupler listening on HOST and the echo solver in the network namespace SOLVER_NETNS (a
// second "host" behind a veth pair).
#include <fcntl.h>
#include <sched.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "core/protocol/messages.hpp"
#include "core/protocol/transport.hpp"
#include "solvers/sdk/solver_sdk.hpp"

namespace {

namespace protocol = cocopp::protocol;
using Clock = std::chrono::steady_clock;

class EchoSolver : public cocopp::sdk::Solver {
 public:
  explicit EchoSolver(std::size_t points) : points_(points) {}
  cocopp::sdk::InterfaceDescription initialize(const cocopp::sdk::RunInfo&) override {
    cocopp::sdk::ModelPart part;
    part.name = "wall";
    part.ids.resize(points_);
    part.coordinates.resize(3 * points_);
    part.input_variables = {"displacement"};
    part.output_variables = {"traction"};
    return {{part}, {}};
  }
  void initialize_step(std::int32_t, double) override {}
  std::vector<double> solve(const std::vector<double>& input) override { return input; }
  void finalize_step() override {}

 private:
  std::size_t points_;
};

struct Statistics {
  double median_us, mean_us, p99_us;
};

Statistics summarize(std::vector<double> times_us) {
  std::sort(times_us.begin(), times_us.end());
  double sum = 0;
  for (double t : times_us) sum += t;
  return {times_us[times_us.size() / 2], sum / times_us.size(),
          times_us[std::min(times_us.size() - 1, times_us.size() * 99 / 100)]};
}

/// Blocking read or write of exactly `size` bytes; aborts on failure (a benchmark, not a tool).
template <class Call>
void exactly(Call call, std::uint8_t* data, std::size_t size) {
  while (size > 0) {
    const ssize_t done = call(data, size);
    if (done <= 0) std::abort();
    data += done;
    size -= static_cast<std::size_t>(done);
  }
}

/// The floor: `doubles` doubles there and back through two anonymous pipes.
Statistics bare_ping_pong(std::size_t doubles, int round_trips) {
  int to_child[2], to_parent[2];
  if (::pipe(to_child) != 0 || ::pipe(to_parent) != 0) std::abort();
  const std::size_t bytes = doubles * sizeof(double);
  std::vector<std::uint8_t> buffer(bytes);
  const int warm_up = std::max(10, round_trips / 10);
  const pid_t child = ::fork();
  if (child == 0) {
    for (int i = 0; i < warm_up + round_trips; ++i) {
      exactly([&](std::uint8_t* d, std::size_t n) { return ::read(to_child[0], d, n); },
              buffer.data(), bytes);
      exactly([&](std::uint8_t* d, std::size_t n) { return ::write(to_parent[1], d, n); },
              buffer.data(), bytes);
    }
    ::_exit(0);
  }
  std::vector<double> times_us;
  for (int i = 0; i < warm_up + round_trips; ++i) {
    const auto start = Clock::now();
    exactly([&](std::uint8_t* d, std::size_t n) { return ::write(to_child[1], d, n); },
            buffer.data(), bytes);
    exactly([&](std::uint8_t* d, std::size_t n) { return ::read(to_parent[0], d, n); },
            buffer.data(), bytes);
    const double elapsed = std::chrono::duration<double, std::micro>(Clock::now() - start).count();
    if (i >= warm_up) times_us.push_back(elapsed);
  }
  ::waitpid(child, nullptr, 0);
  for (int fd : {to_child[0], to_child[1], to_parent[0], to_parent[1]}) ::close(fd);
  return summarize(std::move(times_us));
}

/// Where the TCP transport's two ends are: the coupler's address, the solver's namespace.
struct TcpPlacement {
  std::string host = "127.0.0.1";
  std::string solver_netns;  ///< empty: this one
};

/// The forked solver moves into `netns` (/var/run/netns/<netns>, ip netns's).
void enter_network_namespace(const std::string& netns) {
  if (netns.empty()) return;
  const int fd = ::open(("/var/run/netns/" + netns).c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0 || ::setns(fd, CLONE_NEWNET) != 0) std::abort();
  ::close(fd);
}

Statistics measure(protocol::TransportKind kind, std::size_t doubles, int round_trips,
                   std::chrono::microseconds busy_wait, const TcpPlacement& placement) {
  char pattern[] = "/tmp/cocopp_bench_XXXXXX";
  const std::filesystem::path directory = ::mkdtemp(pattern);
  protocol::CouplerChannelOptions options;
  options.kind = kind;
  options.directory = directory;
  options.busy_wait = busy_wait;
  options.host = placement.host;
  auto channel = protocol::create_coupler_channel(options);
  const pid_t child = ::fork();
  if (child == 0) {
    if (kind == protocol::TransportKind::kTcp) enter_network_namespace(placement.solver_netns);
    for (const auto& [variable, value] : protocol::solver_environment(channel->address()))
      ::setenv(variable.c_str(), value.c_str(), 1);
    EchoSolver solver(doubles / 3);
    char name[] = "echo";
    char* argv[] = {name, nullptr};
    ::_exit(cocopp::sdk::serve(solver, 1, argv));
  }
  channel->connect(10.0, nullptr);
  protocol::decode_hello(channel->receive(10.0, nullptr));
  channel->send(protocol::encode_initialize({0.001, 0}));
  protocol::decode_interface(channel->receive(10.0, nullptr));

  const std::vector<double> values(doubles, 0.125);
  std::vector<double> times_us;
  const int warm_up = std::max(10, round_trips / 10);
  for (int i = 0; i < warm_up + round_trips; ++i) {
    const auto start = Clock::now();
    channel->send(protocol::encode_solve(values.data(), values.size()));
    const auto reply = protocol::decode_data(channel->receive(10.0, nullptr));
    const double elapsed = std::chrono::duration<double, std::micro>(Clock::now() - start).count();
    if (reply.size() != doubles) std::abort();
    if (i >= warm_up) times_us.push_back(elapsed);
  }
  channel->send(protocol::encode_empty(protocol::MessageType::kStop));
  channel->receive(10.0, nullptr);
  ::waitpid(child, nullptr, 0);
  channel.reset();
  std::filesystem::remove_all(directory);

  return summarize(std::move(times_us));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "--help") {
    std::puts(
        "usage: bench_protocol_roundtrip [doubles=300] [round_trips=2000] [HOST SOLVER_NETNS]\n"
        "Round-trip latency of one SOLVE request with its DATA reply, over the pipe, the TCP "
        "(loopback) and the file transport, against a forked echo solver.");
    return 0;
  }
  const std::size_t doubles = argc > 1 ? std::stoul(argv[1]) : 300;
  const int round_trips = argc > 2 ? std::stoi(argv[2]) : 2000;
  TcpPlacement placement;
  if (argc > 4) placement = {argv[3], argv[4]};
  std::printf("SOLVE of %zu doubles + DATA reply, %d round trips each\n", doubles, round_trips);
  const Statistics floor = bare_ping_pong(doubles, round_trips);
  std::printf(
      "bare: median %8.1f us   mean %8.1f us   p99 %8.1f us   (%d round trips, two "
      "anonymous pipes, no protocol)\n",
      floor.median_us, floor.mean_us, floor.p99_us, round_trips);
  struct Mode {
    protocol::TransportKind kind;
    std::chrono::microseconds busy_wait;
    const char* label;
  };
  // The process wrapper's default busy wait is 1 ms (`busy_wait` in the case file).
  const Mode modes[] = {
      {protocol::TransportKind::kPipe, std::chrono::microseconds(0), "pipe, polling"},
      {protocol::TransportKind::kPipe, std::chrono::microseconds(1000), "pipe, busy wait 1 ms"},
      {protocol::TransportKind::kTcp, std::chrono::microseconds(0), "tcp, polling"},
      {protocol::TransportKind::kTcp, std::chrono::microseconds(1000), "tcp, busy wait 1 ms"},
      {protocol::TransportKind::kFile, std::chrono::microseconds(0), "file"}};
  for (const Mode& mode : modes) {
    if (!placement.solver_netns.empty() && mode.kind != protocol::TransportKind::kTcp) continue;
    const int count =
        mode.kind == protocol::TransportKind::kFile ? std::max(1, round_trips / 10) : round_trips;
    const Statistics s = measure(mode.kind, doubles, count, mode.busy_wait, placement);
    std::printf(
        "%-20s: median %8.1f us   mean %8.1f us   p99 %8.1f us   (%d round trips; median %.2f "
        "x bare)\n",
        mode.label, s.median_us, s.mean_us, s.p99_us, count, s.median_us / floor.median_us);
  }
  return 0;
}
