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
// at once and the coupler's retries until the solver is up (or dies, or times out). All reads
// and writes then go through poll() in slices of at most 100 ms, so that the alive check runs.
//
// Both ends ignore SIGPIPE: a write to a pipe whose reader has gone becomes a PeerClosed
// exception instead of killing the process.
#include <chrono>
#include <filesystem>
#include <memory>
#include <string>

#include "core/protocol/transport.hpp"

namespace cocopp::protocol {

class PipeTransport final : public Transport {
 public:
  static constexpr const char* kToSolverFifo = "cocopp_to_solver.fifo";
  static constexpr const char* kFromSolverFifo = "cocopp_from_solver.fifo";

  /// Create both FIFOs in `directory` (replacing stale ones) and open the coupler's read end.
  /// The FIFOs are removed when the transport is destroyed. `busy_wait`: how long a receive
  /// keeps reading without sleeping before it polls (see receive()).
  static std::unique_ptr<PipeTransport> create_for_coupler(
      const std::filesystem::path& directory,
      std::chrono::microseconds busy_wait = std::chrono::microseconds(0));
  /// Open the FIFOs the coupler created in `directory`. `busy_wait` as for the coupler.
  static std::unique_ptr<PipeTransport> open_for_solver(
      const std::filesystem::path& directory, double timeout_seconds,
      const AliveCheck& still_alive_check,
      std::chrono::microseconds busy_wait = std::chrono::microseconds(0));

  ~PipeTransport() override;
  PipeTransport(const PipeTransport&) = delete;
  PipeTransport& operator=(const PipeTransport&) = delete;

  void connect(double timeout_seconds, const AliveCheck& still_alive_check) override;
  using Transport::send;
  void send(const Frame& frame, double timeout_seconds,
            const AliveCheck& still_alive_check) override;
  /// Waits for the next frame. For up to `busy_wait` it reads without sleeping: a message that
  /// comes within it costs no process wake-up (about 50 us on a loaded machine), which on a
  /// fast solver is most of a coupling iteration; a slower one costs at most `busy_wait` of
  /// CPU. Between reads it yields its core, which a process with work may need: with fewer
  /// cores than processes a spin that did not yield slowed the tube run tenfold.
  Frame receive(double timeout_seconds, const AliveCheck& still_alive_check) override;

 private:
  PipeTransport(std::filesystem::path read_path, std::filesystem::path write_path, std::string peer,
                bool owns_fifos);
  void open_read_end();
  /// Wait until `fd` is ready for `events` (or hung up); throws TransportTimeout.
  void wait_for(int fd, short events, const Deadline& deadline, const AliveCheck& check,
                const char* activity) const;
  void read_exactly(std::uint8_t* data, std::size_t size, const Deadline& deadline,
                    const AliveCheck& check);
  void write_all(const std::uint8_t* data, std::size_t size, const Deadline& deadline,
                 const AliveCheck& check);

  std::filesystem::path read_path_;
  std::filesystem::path write_path_;
  std::string peer_;  ///< "solver" or "coupler", for messages
  bool owns_fifos_;
  std::chrono::microseconds busy_wait_{0};
  bool has_read_ = false;  ///< the writer has connected: read() returning 0 now means EOF
  int read_fd_ = -1;
  int write_fd_ = -1;
};

}  // namespace cocopp::protocol
