// Round-trip latency of the solver protocol: the coupler side sends SOLVE with N doubles and
// waits for DATA, against a forked child that serves an echo solver through the SDK, exactly
// as a solver executable would. Measured for the pipe and the file transport.
//
//   bench_protocol_roundtrip [doubles=300] [round_trips=2000]
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
#include "solver_wrappers/sdk/solver_sdk.hpp"

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

Statistics measure(protocol::TransportKind kind, std::size_t doubles, int round_trips) {
  char pattern[] = "/tmp/cocopp_bench_XXXXXX";
  const std::filesystem::path directory = ::mkdtemp(pattern);
  auto channel = protocol::create_coupler_channel(kind, directory);
  const pid_t child = ::fork();
  if (child == 0) {
    ::setenv(protocol::kTransportVariable, protocol::transport_name(kind).c_str(), 1);
    ::setenv(protocol::kChannelVariable, directory.c_str(), 1);
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

  std::sort(times_us.begin(), times_us.end());
  double sum = 0;
  for (double t : times_us) sum += t;
  return {times_us[times_us.size() / 2], sum / times_us.size(),
          times_us[std::min(times_us.size() - 1, times_us.size() * 99 / 100)]};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "--help") {
    std::puts(
        "usage: bench_protocol_roundtrip [doubles=300] [round_trips=2000]\n"
        "Round-trip latency of one SOLVE request with its DATA reply, over the pipe and the "
        "file transport, against a forked echo solver.");
    return 0;
  }
  const std::size_t doubles = argc > 1 ? std::stoul(argv[1]) : 300;
  const int round_trips = argc > 2 ? std::stoi(argv[2]) : 2000;
  std::printf("SOLVE of %zu doubles + DATA reply, %d round trips each\n", doubles, round_trips);
  for (auto kind : {protocol::TransportKind::kPipe, protocol::TransportKind::kFile}) {
    const int count =
        kind == protocol::TransportKind::kFile ? std::max(1, round_trips / 10) : round_trips;
    const Statistics s = measure(kind, doubles, count);
    std::printf("%-4s: median %8.1f us   mean %8.1f us   p99 %8.1f us   (%d round trips)\n",
                protocol::transport_name(kind).c_str(), s.median_us, s.mean_us, s.p99_us, count);
  }
  return 0;
}
