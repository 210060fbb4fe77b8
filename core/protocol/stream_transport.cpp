#include "core/protocol/stream_transport.hpp"

#include <poll.h>
#include <sched.h>
#include <sys/uio.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace cocopp::protocol {

std::string system_error_text(const std::string& what, int error) {
  return what + ": " + std::strerror(error);
}

StreamTransport::~StreamTransport() {
  if (read_fd_ >= 0) ::close(read_fd_);
  if (write_fd_ >= 0 && write_fd_ != read_fd_) ::close(write_fd_);
}

void StreamTransport::fail_io(const std::string& what, int error) const {
  // A pipe whose reader has gone, a connection the peer reset or that TCP's keepalive found
  // dead: the other side is gone, which the coupler reports as such (and keeps the results).
  if (error == EPIPE || error == ECONNRESET || error == ETIMEDOUT || error == EHOSTUNREACH ||
      error == ENETUNREACH)
    throw PeerClosed(
        system_error_text("the connection to the " + peer_ + " was lost (" + what + ")", error));
  throw TransportError(system_error_text("cannot " + what, error));
}

void StreamTransport::wait_for(int fd, short events, const Deadline& deadline,
                               const AliveCheck& check, const char* activity) const {
  for (;;) {
    pollfd request{fd, events, 0};
    const int ready = ::poll(&request, 1, static_cast<int>(deadline.next_slice().count()));
    if (ready > 0) return;  // ready, or POLLHUP/POLLERR: the next read/write tells which
    if (ready < 0 && errno != EINTR)
      throw TransportError(system_error_text(std::string("poll while ") + activity, errno));
    if (deadline.expired())
      throw TransportTimeout(std::string("timed out ") + activity + " the " + peer_);
    if (check) check();
  }
}

void StreamTransport::read_exactly(std::uint8_t* data, std::size_t size, const Deadline& deadline,
                                   const AliveCheck& check) {
  const auto busy_until = std::chrono::steady_clock::now() + busy_wait_;
  while (size > 0) {
    // Poll (and sleep) once the busy wait is over. Before the writer has ever connected,
    // read() would return 0 (not EOF): poll first then.
    if (!has_read_ || std::chrono::steady_clock::now() >= busy_until)
      wait_for(read_fd_, POLLIN, deadline, check, "waiting for a message from");
    const ssize_t got = ::read(read_fd_, data, size);
    if (got > 0) {
      has_read_ = true;
      data += got;
      size -= static_cast<std::size_t>(got);
    } else if (got == 0) {
      throw PeerClosed("the " + peer_ + " closed " + link_);
    } else if (errno == EAGAIN) {
      ::sched_yield();  // nothing yet: let a process with work have the core
    } else if (errno != EINTR) {
      fail_io("read " + read_name_, errno);
    }
  }
}

void StreamTransport::write_all(const std::uint8_t* data, std::size_t size,
                                const Deadline& deadline, const AliveCheck& check) {
  while (size > 0) {
    const ssize_t put = ::write(write_fd_, data, size);
    if (put > 0) {
      data += put;
      size -= static_cast<std::size_t>(put);
    } else if (put < 0 && errno == EAGAIN) {
      wait_for(write_fd_, POLLOUT, deadline, check, "sending a message to");
    } else if (put < 0 && errno != EINTR) {
      fail_io("write " + write_name_, errno);
    }
  }
}

void StreamTransport::send(const Frame& frame, double timeout_seconds,
                           const AliveCheck& still_alive_check) {
  if (write_fd_ < 0) throw TransportError("transport to the " + peer_ + " used before connect()");
  std::uint8_t prefix[kLengthPrefixBytes];
  encode_length_prefix(frame.size(), prefix);
  const Deadline deadline(timeout_seconds);
  // One system call for prefix and payload, so the reader wakes up once per message.
  iovec parts[2] = {{prefix, sizeof prefix},
                    {const_cast<std::uint8_t*>(frame.data()), frame.size()}};
  const ssize_t put = ::writev(write_fd_, parts, 2);
  const std::size_t written = put > 0 ? static_cast<std::size_t>(put) : 0;
  // Whatever the channel did not take at once (or an error to report) goes the careful way.
  if (written < sizeof prefix)
    write_all(prefix + written, sizeof prefix - written, deadline, still_alive_check);
  const std::size_t payload_written = written > sizeof prefix ? written - sizeof prefix : 0;
  write_all(frame.data() + payload_written, frame.size() - payload_written, deadline,
            still_alive_check);
}

Frame StreamTransport::receive(double timeout_seconds, const AliveCheck& still_alive_check) {
  const Deadline deadline(timeout_seconds);
  std::uint8_t prefix[kLengthPrefixBytes];
  read_exactly(prefix, sizeof prefix, deadline, still_alive_check);
  const std::size_t length = decode_length_prefix(prefix);
  check_payload_size(length);
  // The buffer grows with what arrives: a length that is a lie costs no memory up front.
  constexpr std::size_t kChunk = std::size_t(1) << 20;
  Frame frame;
  while (frame.size() < length) {
    const std::size_t start = frame.size();
    frame.resize(std::min(length, start + kChunk));
    read_exactly(frame.data() + start, frame.size() - start, deadline, still_alive_check);
  }
  return frame;
}

}  // namespace cocopp::protocol
