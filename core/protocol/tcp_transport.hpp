#pragma once
// Frames over one TCP connection, for a solver on another host (docs/clusters.md).
//
// The coupler listens on the address the case names (loopback by default) before it launches
// the solver, and hands the solver "host:port" and a per-run secret through the solver's
// environment (COCOPP_CHANNEL, COCOPP_TOKEN: never on a command line). The solver connects and
// first sends kGreeting followed by the secret; the coupler answers kWelcome (which the solver
// reads before its first frame) and from then on both sides exchange frames as over the pipes. A
// peer that sends anything else, nothing within kGreetingSeconds, or closes, is refused and
// recorded (refused()); it never gets a frame. Once the solver is in, the coupler stops listening,
// so a second client on the port is refused by the kernel.
//
// A lost link is noticed without the peer's help: TCP keepalive probes an idle connection
// every 2 s after 5 s and gives up after 5 unanswered probes, and unacknowledged data is
// given up after 20 s (TCP_USER_TIMEOUT); the next read or write then fails as PeerClosed.
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "core/protocol/stream_transport.hpp"

namespace cocopp::protocol {

class TcpTransport final : public StreamTransport {
 public:
  static constexpr const char kGreeting[] = "COCOPP-TCP-1 ";  ///< then the token, then '\n'
  static constexpr const char kWelcome[] = "COCOPP-WELCOME\n";
  static constexpr double kGreetingSeconds = 10.0;
  static constexpr std::size_t kTokenCharacters = 64;  ///< 32 random bytes, in hex

  /// Coupler side: listen on `host` (an address or a name of this machine) at `port` (0: a
  /// free one), with a fresh token.
  static std::unique_ptr<TcpTransport> listen(
      const std::string& host, int port,
      std::chrono::microseconds busy_wait = std::chrono::microseconds(0));
  /// Solver side: connect to `channel` ("host:port", "[v6]:port"), prove `token` and wait for
  /// the welcome, all within `timeout_seconds`.
  static std::unique_ptr<TcpTransport> connect_to(
      const std::string& channel, const std::string& token, double timeout_seconds,
      const AliveCheck& still_alive_check,
      std::chrono::microseconds busy_wait = std::chrono::microseconds(0));

  ~TcpTransport() override;

  /// Coupler side: accept connections until one proves the token (refusing the others), then
  /// stop listening. Throws TransportTimeout naming the peers refused meanwhile.
  void connect(double timeout_seconds, const AliveCheck& still_alive_check) override;
  ChannelAddress address() const override;
  /// Solver side: the first receive first takes the coupler's welcome (so that opening the
  /// channel never waits for the coupler); a refusal then says so.
  using StreamTransport::receive;
  Frame receive(double timeout_seconds, const AliveCheck& still_alive_check) override;
  /// The peers refused so far, each "address: why", for the coupler's log.
  const std::vector<std::string>& refused() const { return refused_; }

 private:
  TcpTransport(std::string peer, std::chrono::microseconds busy_wait)
      : StreamTransport(std::move(peer), busy_wait) {}
  struct Pending;
  /// A connection that proved the token: it becomes the channel.
  void adopt(int fd, const std::string& peer_address);
  void refuse(Pending& pending, const std::string& why);

  int listen_fd_ = -1;
  std::string host_;
  int port_ = 0;
  std::string token_;
  std::vector<std::string> refused_;
  std::string coupler_channel_;   ///< solver side: "host:port", for messages
  bool welcome_pending_ = false;  ///< solver side: the welcome is still to be read
};

/// Splits "host:port" or "[v6 address]:port"; throws TransportError for anything else.
std::pair<std::string, int> split_host_port(const std::string& channel);

}  // namespace cocopp::protocol
