#pragma once
// The default transport: two named pipes (FIFOs) in the channel directory.
//
//   cocopp_to_solver.fifo    requests, coupler -> solver
//   cocopp_from_solver.fifo  replies,  solver -> coupler
//
// Named rather than anonymous pipes because mpirun does not pass inherited file descriptors on
// to its ranks, while rank 0 can always open a path.
//
// No open() may block forever (the other side may never come): each side first opens its read
// end with O_NONBLOCK, which succeeds at once, then opens its write end with O_NONBLOCK in a
// retry loop, which fails with ENXIO until the other side has opened its read end. The
// coupler opens its read end before it launches the solver, so the solver's connect succeeds
// at once and the coupler's retries until the solver is up (or dies, or times out). Frames
// then go as StreamTransport sends them.
//
// Both ends ignore SIGPIPE: a write to a pipe whose reader has gone becomes a PeerClosed
// exception instead of killing the process.
#include <chrono>
#include <filesystem>
#include <memory>
#include <string>

#include "core/protocol/stream_transport.hpp"

namespace cocopp::protocol {

class PipeTransport final : public StreamTransport {
 public:
  static constexpr const char* kToSolverFifo = "cocopp_to_solver.fifo";
  static constexpr const char* kFromSolverFifo = "cocopp_from_solver.fifo";

  /// Create both FIFOs in `directory` (replacing stale ones) and open the coupler's read end.
  /// The FIFOs are removed when the transport is destroyed. `busy_wait`: how long a receive
  /// keeps reading without sleeping before it polls (StreamTransport::receive).
  static std::unique_ptr<PipeTransport> create_for_coupler(
      const std::filesystem::path& directory,
      std::chrono::microseconds busy_wait = std::chrono::microseconds(0));
  /// Open the FIFOs the coupler created in `directory`. `busy_wait` as for the coupler.
  static std::unique_ptr<PipeTransport> open_for_solver(
      const std::filesystem::path& directory, double timeout_seconds,
      const AliveCheck& still_alive_check,
      std::chrono::microseconds busy_wait = std::chrono::microseconds(0));

  ~PipeTransport() override;

  void connect(double timeout_seconds, const AliveCheck& still_alive_check) override;
  ChannelAddress address() const override;

 private:
  PipeTransport(std::filesystem::path read_path, std::filesystem::path write_path, std::string peer,
                bool owns_fifos, std::chrono::microseconds busy_wait);
  void open_read_end();

  std::filesystem::path read_path_;
  std::filesystem::path write_path_;
  bool owns_fifos_;
};

}  // namespace cocopp::protocol
