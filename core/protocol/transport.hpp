#pragma once
// Transports carry frames between the coupler and one solver. Both ends use the same classes;
// which end is which only matters when the channel is set up:
//
//   coupler: create_coupler_channel() -> launch the solver with solver_environment(address())
//            -> connect() -> receive HELLO ...
//   solver:  open_solver_channel(channel_from_environment()) -> send HELLO -> receive requests
//
// Every wait has a timeout and calls a still-alive check at least every 100 ms: the coupler's
// check throws when the solver process has died, so a crashed solver never leaves the coupler
// waiting for a message that cannot come.
#include <chrono>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/protocol/frame.hpp"

namespace cocopp::protocol {

/// Called while waiting; throws to abort the wait (its exception propagates unchanged).
using AliveCheck = std::function<void()>;

constexpr double kWaitForever = std::numeric_limits<double>::infinity();
/// Longest time between two calls of the alive check.
constexpr std::chrono::milliseconds kAliveCheckInterval{100};

/// Environment variables through which the coupler tells a solver where its channel is.
constexpr const char* kTransportVariable = "COCOPP_TRANSPORT";  ///< "pipe", "file" or "tcp"
/// pipe, file: the channel's absolute directory; tcp: the coupler's "host:port"
constexpr const char* kChannelVariable = "COCOPP_CHANNEL";
/// tcp: the run's secret, which the solver sends first to be let in (never on a command line)
constexpr const char* kTokenVariable = "COCOPP_TOKEN";
/// A solver the user starts (`started_by: user`): the file holding the three variables above,
/// which the coupler writes (mode 0600) into the solver's working directory.
constexpr const char* kChannelFileVariable = "COCOPP_CHANNEL_FILE";
/// Seconds the solver reads its request pipe without sleeping ("0.001"; unset: 0).
constexpr const char* kBusyWaitVariable = "COCOPP_BUSY_WAIT";

/// The channel cannot be used (I/O error, missing FIFO, ...).
class TransportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Nothing arrived (or could be sent) within the timeout.
class TransportTimeout : public TransportError {
 public:
  using TransportError::TransportError;
};

/// The other side closed its end: it exited or crashed.
class PeerClosed : public TransportError {
 public:
  using TransportError::TransportError;
};

enum class TransportKind { kPipe, kFile, kTcp };

/// "pipe", "file" or "tcp"; throws std::invalid_argument otherwise.
TransportKind parse_transport_kind(const std::string& name);
std::string transport_name(TransportKind kind);

/// Where a solver finds its channel: what the coupler puts into the solver's environment.
struct ChannelAddress {
  TransportKind kind = TransportKind::kPipe;
  std::string channel;  ///< pipe, file: the directory; tcp: "host:port"
  std::string token;    ///< tcp: the run's secret; empty otherwise
};

/// The variables that tell a solver `address`: COCOPP_TRANSPORT, COCOPP_CHANNEL (and
/// COCOPP_TOKEN for tcp).
std::vector<std::pair<std::string, std::string>> solver_environment(const ChannelAddress& address);
/// Solver side: the address in this process's environment, or in the file COCOPP_CHANNEL_FILE
/// names (lines VARIABLE=value, # comments); throws TransportError naming the variable or the
/// file that is missing or wrong.
ChannelAddress channel_from_environment();
/// True if this process was given a channel (the variables, or the file).
bool channel_in_environment();
/// Coupler side, for a solver the user starts: writes solver_environment(address) to `file`
/// (readable by the user only, written whole or not at all).
void write_channel_file(const std::filesystem::path& file, const ChannelAddress& address,
                        const std::string& solver_name);

class Transport {
 public:
  virtual ~Transport() = default;

  /// Coupler side: where the solver finds this channel.
  virtual ChannelAddress address() const = 0;

  /// Coupler side, after launching the solver: wait until the solver has opened its end.
  virtual void connect(double timeout_seconds, const AliveCheck& still_alive_check) = 0;

  virtual void send(const Frame& frame, double timeout_seconds,
                    const AliveCheck& still_alive_check) = 0;
  void send(const Frame& frame) { send(frame, kWaitForever, nullptr); }

  /// The next frame; throws TransportTimeout, PeerClosed, ProtocolError (corrupt frame, or
  /// one longer than max_payload()).
  virtual Frame receive(double timeout_seconds, const AliveCheck& still_alive_check) = 0;

  /// The longest payload receive() accepts (kMaxPayloadBytes until set): once the interface
  /// is known, the coupler bounds every reply by what it can need, so that a lying length
  /// prefix or a huge message file costs neither memory nor time.
  void set_max_payload(std::size_t bytes) { max_payload_ = bytes; }
  std::size_t max_payload() const { return max_payload_; }

 protected:
  /// Throws ProtocolError if a frame of `bytes` exceeds max_payload().
  void check_payload_size(std::size_t bytes) const;

 private:
  std::size_t max_payload_ = kMaxPayloadBytes;
};

/// What the coupler's end of a channel is made from.
struct CouplerChannelOptions {
  TransportKind kind = TransportKind::kPipe;
  /// pipe, file: where the channel lives (the solver's working directory)
  std::filesystem::path directory;
  /// pipe, tcp: a receive reads this long without sleeping before it polls
  /// (StreamTransport::receive)
  std::chrono::microseconds busy_wait{0};
  /// tcp: the address to listen on (and that the solver connects to), and the port (0: any
  /// free one, which address() then reports)
  std::string host = "127.0.0.1";
  int port = 0;
};

/// Coupler side, before launching the solver: create the channel (the FIFOs; a cleanup of
/// stale message files; a listening socket). The returned transport removes what it created
/// when it is destroyed.
std::unique_ptr<Transport> create_coupler_channel(const CouplerChannelOptions& options);
/// The same for a pipe or file channel in `directory`.
std::unique_ptr<Transport> create_coupler_channel(
    TransportKind kind, const std::filesystem::path& directory,
    std::chrono::microseconds busy_wait = std::chrono::microseconds(0));

/// Solver side: open the channel the coupler created at `address`; `busy_wait` as above.
std::unique_ptr<Transport> open_solver_channel(
    const ChannelAddress& address, double timeout_seconds, const AliveCheck& still_alive_check,
    std::chrono::microseconds busy_wait = std::chrono::microseconds(0));
/// The same for a pipe or file channel in `directory`.
std::unique_ptr<Transport> open_solver_channel(
    TransportKind kind, const std::filesystem::path& directory, double timeout_seconds,
    const AliveCheck& still_alive_check,
    std::chrono::microseconds busy_wait = std::chrono::microseconds(0));
/// The solver's busy wait from $COCOPP_BUSY_WAIT (seconds; unset: 0). Throws TransportError
/// for a value that is not a number in [0, 0.1].
std::chrono::microseconds busy_wait_from_environment();

/// A point in time `seconds` from now (never, for infinity).
class Deadline {
 public:
  explicit Deadline(double seconds);
  bool expired() const;
  /// Time to wait before the next alive check: min(remaining, kAliveCheckInterval).
  std::chrono::milliseconds next_slice() const;

 private:
  using Clock = std::chrono::steady_clock;
  bool forever_;
  Clock::time_point end_;
};

/// "0.5 s", "600 s": timeouts in messages.
std::string seconds_text(double seconds);

}  // namespace cocopp::protocol
