#include "core/protocol/pipe_transport.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sched.h>
#include <sys/stat.h>
#include <sys/uio.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <thread>

namespace cocopp::protocol {

namespace {

std::string system_error_text(const std::string& what, int error) {
  return what + ": " + std::strerror(error);
}

void make_fifo(const std::filesystem::path& path) {
  std::error_code ignored;
  std::filesystem::remove(path, ignored);  // a stale FIFO of an earlier run
  if (::mkfifo(path.c_str(), 0600) != 0)
    throw TransportError(system_error_text("cannot create the named pipe " + path.string(), errno));
}

void ignore_sigpipe() {
  std::signal(SIGPIPE, SIG_IGN);
}

}  // namespace

PipeTransport::PipeTransport(std::filesystem::path read_path, std::filesystem::path write_path,
                             std::string peer, bool owns_fifos)
    : read_path_(std::move(read_path)),
      write_path_(std::move(write_path)),
      peer_(std::move(peer)),
      owns_fifos_(owns_fifos) {}

std::unique_ptr<PipeTransport> PipeTransport::create_for_coupler(
    const std::filesystem::path& directory, std::chrono::microseconds busy_wait) {
  if (!std::filesystem::is_directory(directory))
    throw TransportError("channel directory " + directory.string() + " does not exist");
  ignore_sigpipe();
  std::unique_ptr<PipeTransport> transport(new PipeTransport(
      directory / kFromSolverFifo, directory / kToSolverFifo, "solver", /*owns_fifos=*/true));
  transport->busy_wait_ = busy_wait;
  make_fifo(transport->write_path_);
  make_fifo(transport->read_path_);
  transport->open_read_end();
  return transport;
}

std::unique_ptr<PipeTransport> PipeTransport::open_for_solver(
    const std::filesystem::path& directory, double timeout_seconds,
    const AliveCheck& still_alive_check, std::chrono::microseconds busy_wait) {
  ignore_sigpipe();
  std::unique_ptr<PipeTransport> transport(new PipeTransport(
      directory / kToSolverFifo, directory / kFromSolverFifo, "coupler", /*owns_fifos=*/false));
  transport->busy_wait_ = busy_wait;
  transport->open_read_end();
  transport->connect(timeout_seconds, still_alive_check);
  return transport;
}

PipeTransport::~PipeTransport() {
  if (read_fd_ >= 0) ::close(read_fd_);
  if (write_fd_ >= 0) ::close(write_fd_);
  if (owns_fifos_) {
    std::error_code ignored;
    std::filesystem::remove(read_path_, ignored);
    std::filesystem::remove(write_path_, ignored);
  }
}

// O_NONBLOCK: opening a FIFO's read end this way succeeds without a writer. O_CLOEXEC: a solver
// launched later must not inherit this end, or it would keep the pipe open after we close it.
void PipeTransport::open_read_end() {
  struct stat info {};
  if (::stat(read_path_.c_str(), &info) != 0 || !S_ISFIFO(info.st_mode))
    throw TransportError("no named pipe " + read_path_.string() + " (is the " + peer_ +
                         " running and using the pipe transport?)");
  read_fd_ = ::open(read_path_.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (read_fd_ < 0)
    throw TransportError(system_error_text("cannot open " + read_path_.string(), errno));
}

void PipeTransport::connect(double timeout_seconds, const AliveCheck& still_alive_check) {
  if (write_fd_ >= 0) return;
  const Deadline deadline(timeout_seconds);
  auto pause = std::chrono::milliseconds(1);
  for (;;) {
    // ENXIO until the other side has opened its read end.
    write_fd_ = ::open(write_path_.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
    if (write_fd_ >= 0) return;
    if (errno == EINTR) continue;
    if (errno != ENXIO)
      throw TransportError(system_error_text("cannot open " + write_path_.string(), errno));
    if (deadline.expired())
      throw TransportTimeout("the " + peer_ + " did not open " + write_path_.string() + " within " +
                             seconds_text(timeout_seconds));
    if (still_alive_check) still_alive_check();
    std::this_thread::sleep_for(std::min(pause, deadline.next_slice()));
    pause = std::min(pause * 2, std::chrono::milliseconds(50));
  }
}

void PipeTransport::wait_for(int fd, short events, const Deadline& deadline,
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

void PipeTransport::read_exactly(std::uint8_t* data, std::size_t size, const Deadline& deadline,
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
      throw PeerClosed("the " + peer_ + " closed the pipe");
    } else if (errno == EAGAIN) {
      ::sched_yield();  // nothing yet: let a process with work have the core
    } else if (errno != EINTR) {
      throw TransportError(system_error_text("cannot read " + read_path_.string(), errno));
    }
  }
}

void PipeTransport::write_all(const std::uint8_t* data, std::size_t size, const Deadline& deadline,
                              const AliveCheck& check) {
  while (size > 0) {
    const ssize_t put = ::write(write_fd_, data, size);
    if (put > 0) {
      data += put;
      size -= static_cast<std::size_t>(put);
    } else if (put < 0 && errno == EPIPE) {
      throw PeerClosed("the " + peer_ + " closed the pipe");
    } else if (put < 0 && errno == EAGAIN) {
      wait_for(write_fd_, POLLOUT, deadline, check, "sending a message to");
    } else if (put < 0 && errno != EINTR) {
      throw TransportError(system_error_text("cannot write " + write_path_.string(), errno));
    }
  }
}

void PipeTransport::send(const Frame& frame, double timeout_seconds,
                         const AliveCheck& still_alive_check) {
  if (write_fd_ < 0) throw TransportError("pipe transport used before connect()");
  std::uint8_t prefix[kLengthPrefixBytes];
  encode_length_prefix(frame.size(), prefix);
  const Deadline deadline(timeout_seconds);
  // One system call for prefix and payload, so the reader wakes up once per message.
  iovec parts[2] = {{prefix, sizeof prefix},
                    {const_cast<std::uint8_t*>(frame.data()), frame.size()}};
  const ssize_t put = ::writev(write_fd_, parts, 2);
  const std::size_t written = put > 0 ? static_cast<std::size_t>(put) : 0;
  // Whatever the pipe did not take at once (or an error to report) goes the careful way.
  if (written < sizeof prefix)
    write_all(prefix + written, sizeof prefix - written, deadline, still_alive_check);
  const std::size_t payload_written = written > sizeof prefix ? written - sizeof prefix : 0;
  write_all(frame.data() + payload_written, frame.size() - payload_written, deadline,
            still_alive_check);
}

Frame PipeTransport::receive(double timeout_seconds, const AliveCheck& still_alive_check) {
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
