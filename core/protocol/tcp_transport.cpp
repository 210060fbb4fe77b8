#include "core/protocol/tcp_transport.hpp"

#include <arpa/inet.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/random.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <thread>

namespace cocopp::protocol {

namespace {

constexpr std::size_t kGreetingBytes =
    sizeof(TcpTransport::kGreeting) - 1 + TcpTransport::kTokenCharacters + 1;
/// Connections waiting to send their greeting at once; more are refused oldest first.
constexpr std::size_t kMaxPending = 8;

std::string new_token() {
  unsigned char bytes[TcpTransport::kTokenCharacters / 2];
  std::size_t got = 0;
  while (got < sizeof bytes) {
    const ssize_t n = ::getrandom(bytes + got, sizeof bytes - got, 0);
    if (n < 0 && errno != EINTR) throw TransportError(system_error_text("getrandom", errno));
    if (n > 0) got += static_cast<std::size_t>(n);
  }
  static const char* digits = "0123456789abcdef";
  std::string token;
  for (unsigned char byte : bytes) {
    token += digits[byte >> 4];
    token += digits[byte & 15];
  }
  return token;
}

/// Equal strings, in a time that does not tell how much of a guess was right.
bool same_secret(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char difference = 0;
  for (std::size_t i = 0; i < a.size(); ++i) difference |= static_cast<unsigned char>(a[i] ^ b[i]);
  return difference == 0;
}

std::string describe(const sockaddr* address) {
  char host[NI_MAXHOST] = "?", port[NI_MAXSERV] = "?";
  const socklen_t size =
      address->sa_family == AF_INET6 ? sizeof(sockaddr_in6) : sizeof(sockaddr_in);
  ::getnameinfo(address, size, host, sizeof host, port, sizeof port,
                NI_NUMERICHOST | NI_NUMERICSERV);
  return address->sa_family == AF_INET6 ? "[" + std::string(host) + "]:" + port
                                        : std::string(host) + ":" + port;
}

/// Low latency for small frames, and a dead link noticed within about 20 s (the header).
void tune(int fd) {
  const int on = 1, idle = 5, interval = 2, count = 5;
  const unsigned user_timeout_ms = 20000;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
  ::setsockopt(fd, SOL_SOCKET, SO_KEEPALIVE, &on, sizeof on);
  ::setsockopt(fd, IPPROTO_TCP, TCP_KEEPIDLE, &idle, sizeof idle);
  ::setsockopt(fd, IPPROTO_TCP, TCP_KEEPINTVL, &interval, sizeof interval);
  ::setsockopt(fd, IPPROTO_TCP, TCP_KEEPCNT, &count, sizeof count);
  ::setsockopt(fd, IPPROTO_TCP, TCP_USER_TIMEOUT, &user_timeout_ms, sizeof user_timeout_ms);
}

struct AddressList {
  addrinfo* first = nullptr;
  ~AddressList() {
    if (first != nullptr) ::freeaddrinfo(first);
  }
};

AddressList resolve(const std::string& host, int port, bool passive) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_NUMERICSERV | (passive ? AI_PASSIVE : 0);
  AddressList list;
  const int status = ::getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &list.first);
  if (status != 0) throw TransportError("cannot resolve '" + host + "': " + ::gai_strerror(status));
  return list;
}

/// A non-blocking connect that gives up at `deadline`: 0, or the errno it failed with.
int connect_within(int fd, const sockaddr* address, socklen_t size, const Deadline& deadline,
                   const AliveCheck& check) {
  if (::connect(fd, address, size) == 0) return 0;
  if (errno != EINPROGRESS) return errno;
  for (;;) {
    pollfd request{fd, POLLOUT, 0};
    const int ready = ::poll(&request, 1, static_cast<int>(deadline.next_slice().count()));
    if (ready > 0) {
      int error = 0;
      socklen_t length = sizeof error;
      ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &length);
      return error;
    }
    if (ready < 0 && errno != EINTR) return errno;
    if (deadline.expired()) return ETIMEDOUT;
    if (check) check();
  }
}

}  // namespace

struct TcpTransport::Pending {
  int fd;
  std::string address;
  std::chrono::steady_clock::time_point since;
  std::string received;
};

std::pair<std::string, int> split_host_port(const std::string& channel) {
  const std::size_t colon = channel.rfind(':');
  std::string host = colon == std::string::npos ? "" : channel.substr(0, colon);
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']')
    host = host.substr(1, host.size() - 2);
  const std::string port_text = colon == std::string::npos ? "" : channel.substr(colon + 1);
  int port = 0;
  const bool digits = !port_text.empty() && port_text.size() <= 5 &&
                      std::all_of(port_text.begin(), port_text.end(), ::isdigit);
  if (digits) port = std::stoi(port_text);
  if (host.empty() || !digits || port < 1 || port > 65535)
    throw TransportError("'" + channel + "' is not host:port (e.g. 10.0.0.2:40123)");
  return {host, port};
}

std::unique_ptr<TcpTransport> TcpTransport::listen(const std::string& host, int port,
                                                   std::chrono::microseconds busy_wait) {
  std::signal(SIGPIPE, SIG_IGN);
  if (port < 0 || port > 65535)
    throw TransportError("port " + std::to_string(port) + " is not in 0..65535");
  std::unique_ptr<TcpTransport> transport(new TcpTransport("solver", busy_wait));
  const AddressList addresses = resolve(host, port, /*passive=*/true);
  int error = 0;
  for (addrinfo* a = addresses.first; a != nullptr; a = a->ai_next) {
    const int fd = ::socket(a->ai_family, a->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) {
      error = errno;
      continue;
    }
    const int on = 1;
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
    if (::bind(fd, a->ai_addr, a->ai_addrlen) == 0 && ::listen(fd, 16) == 0) {
      transport->listen_fd_ = fd;
      break;
    }
    error = errno;
    ::close(fd);
  }
  if (transport->listen_fd_ < 0)
    throw TransportError(
        system_error_text("cannot listen on " + host + ":" + std::to_string(port) +
                              " (an address of this machine? a port another program uses?)",
                          error));
  sockaddr_storage bound{};
  socklen_t size = sizeof bound;
  ::getsockname(transport->listen_fd_, reinterpret_cast<sockaddr*>(&bound), &size);
  transport->port_ =
      ntohs(bound.ss_family == AF_INET6 ? reinterpret_cast<sockaddr_in6*>(&bound)->sin6_port
                                        : reinterpret_cast<sockaddr_in*>(&bound)->sin_port);
  transport->host_ = host;
  transport->token_ = new_token();
  return transport;
}

TcpTransport::~TcpTransport() {
  if (listen_fd_ >= 0) ::close(listen_fd_);
}

ChannelAddress TcpTransport::address() const {
  const bool v6 = host_.find(':') != std::string::npos;
  return {TransportKind::kTcp, (v6 ? "[" + host_ + "]" : host_) + ":" + std::to_string(port_),
          token_};
}

void TcpTransport::refuse(Pending& pending, const std::string& why) {
  refused_.push_back(pending.address + ": " + why);
  ::close(pending.fd);
  pending.fd = -1;
}

void TcpTransport::adopt(int fd, const std::string& peer_address) {
  tune(fd);
  read_fd_ = write_fd_ = fd;
  read_name_ = write_name_ = peer_address;
  link_ = "the connection";
  has_read_ = true;  // a socket's read() returning 0 is always the end
}

void TcpTransport::connect(double timeout_seconds, const AliveCheck& still_alive_check) {
  if (read_fd_ >= 0) return;
  const Deadline deadline(timeout_seconds);
  const std::string expected = kGreeting + token_ + "\n";
  std::vector<Pending> pending;
  const auto close_all = [&] {
    for (auto& p : pending)
      if (p.fd >= 0) refuse(p, "another peer proved the token first");
  };
  for (;;) {
    std::vector<pollfd> polled = {{listen_fd_, POLLIN, 0}};
    for (const auto& p : pending) polled.push_back({p.fd, POLLIN, 0});
    const int ready =
        ::poll(polled.data(), polled.size(), static_cast<int>(deadline.next_slice().count()));
    if (ready < 0 && errno != EINTR)
      throw TransportError(system_error_text("poll while waiting for the solver", errno));
    if (ready > 0 && (polled[0].revents & POLLIN)) {
      sockaddr_storage from{};
      socklen_t size = sizeof from;
      const int fd = ::accept4(listen_fd_, reinterpret_cast<sockaddr*>(&from), &size,
                               SOCK_NONBLOCK | SOCK_CLOEXEC);
      if (fd >= 0) {
        if (pending.size() >= kMaxPending) {
          refuse(pending.front(), "too many connections waiting");
          pending.erase(pending.begin());
        }
        pending.push_back({fd, describe(reinterpret_cast<sockaddr*>(&from)),
                           std::chrono::steady_clock::now(), ""});
      }
    }
    const auto now = std::chrono::steady_clock::now();
    for (auto& p : pending) {
      char buffer[kGreetingBytes];
      const std::size_t want = kGreetingBytes - p.received.size();
      const ssize_t got = ::read(p.fd, buffer, want);
      if (got > 0) p.received.append(buffer, static_cast<std::size_t>(got));
      // The greeting's fixed words are checked as they come; the token only whole, so that
      // how soon a guess is refused tells nothing about it.
      const std::size_t words = std::min(p.received.size(), sizeof kGreeting - 1);
      if (got == 0 || (got < 0 && errno != EAGAIN && errno != EINTR)) {
        refuse(p, "closed before it sent the token");
      } else if (p.received.compare(0, words, kGreeting, words) != 0) {
        refuse(p, "not a cocopp solver (it did not greet as one)");
      } else if (p.received.size() == kGreetingBytes) {
        if (!same_secret(p.received, expected)) {
          refuse(p, "a wrong token");
          continue;
        }
        const int fd = p.fd;
        const std::string from = p.address;
        p.fd = -1;
        close_all();
        ::close(listen_fd_);
        listen_fd_ = -1;
        adopt(fd, from);
        write_all(reinterpret_cast<const std::uint8_t*>(kWelcome), sizeof kWelcome - 1,
                  Deadline(kGreetingSeconds), still_alive_check);
        return;
      } else if (now - p.since > std::chrono::duration<double>(kGreetingSeconds)) {
        refuse(p, "sent no token within " + seconds_text(kGreetingSeconds));
      }
    }
    pending.erase(
        std::remove_if(pending.begin(), pending.end(), [](const Pending& p) { return p.fd < 0; }),
        pending.end());
    if (deadline.expired()) {
      close_all();
      std::string why;
      for (const auto& r : refused_) why += "; refused " + r;
      throw TransportTimeout("no solver connected to " + address().channel +
                             " with the token within " + seconds_text(timeout_seconds) + why);
    }
    if (still_alive_check) still_alive_check();
  }
}

std::unique_ptr<TcpTransport> TcpTransport::connect_to(const std::string& channel,
                                                       const std::string& token,
                                                       double timeout_seconds,
                                                       const AliveCheck& still_alive_check,
                                                       std::chrono::microseconds busy_wait) {
  std::signal(SIGPIPE, SIG_IGN);
  const auto [host, port] = split_host_port(channel);
  if (token.size() != kTokenCharacters)
    throw TransportError(std::string(kTokenVariable) + " is not the run's token (" +
                         std::to_string(kTokenCharacters) + " hex digits)");
  const Deadline deadline(timeout_seconds);
  std::unique_ptr<TcpTransport> transport(new TcpTransport("coupler", busy_wait));
  int fd = -1;
  std::string last_error = "no address";
  auto pause = std::chrono::milliseconds(10);
  while (fd < 0) {
    const AddressList addresses = resolve(host, port, /*passive=*/false);
    for (addrinfo* a = addresses.first; a != nullptr && fd < 0; a = a->ai_next) {
      fd = ::socket(a->ai_family, a->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
      if (fd < 0) continue;
      // The coupler listens before it launches the solver, so a refusal means a wrong address
      // or a network still coming up: retried until the deadline.
      const int error = connect_within(fd, a->ai_addr, a->ai_addrlen, deadline, still_alive_check);
      if (error != 0) {
        last_error = std::strerror(error);
        ::close(fd);
        fd = -1;
      }
    }
    if (fd >= 0) break;
    if (deadline.expired())
      throw TransportTimeout("cannot connect to the coupler at " + channel + " within " +
                             seconds_text(timeout_seconds) + ": " + last_error);
    if (still_alive_check) still_alive_check();
    std::this_thread::sleep_for(std::min(pause, deadline.next_slice()));
    pause = std::min(pause * 2, std::chrono::milliseconds(200));
  }
  transport->adopt(fd, channel);
  const std::string greeting = kGreeting + token + "\n";
  transport->write_all(reinterpret_cast<const std::uint8_t*>(greeting.data()), greeting.size(),
                       deadline, still_alive_check);
  transport->coupler_channel_ = channel;
  transport->welcome_pending_ = true;
  return transport;
}

Frame TcpTransport::receive(double timeout_seconds, const AliveCheck& still_alive_check) {
  if (welcome_pending_) {
    std::string welcome(sizeof kWelcome - 1, '\0');
    try {
      read_exactly(reinterpret_cast<std::uint8_t*>(welcome.data()), welcome.size(),
                   Deadline(timeout_seconds), still_alive_check);
    } catch (const PeerClosed&) {
      throw TransportError("the coupler at " + coupler_channel_ + " refused this solver (is " +
                           kTokenVariable + " this run's token?)");
    }
    if (welcome != kWelcome)
      throw TransportError("the peer at " + coupler_channel_ + " is not a cocopp coupler");
    welcome_pending_ = false;
  }
  return StreamTransport::receive(timeout_seconds, still_alive_check);
}

}  // namespace cocopp::protocol
