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
                             std::string peer, bool owns_fifos, std::chrono::microseconds busy_wait)
    : StreamTransport(std::move(peer), busy_wait),
      read_path_(std::move(read_path)),
      write_path_(std::move(write_path)),
      owns_fifos_(owns_fifos) {
  read_name_ = read_path_.string();
  write_name_ = write_path_.string();
}

std::unique_ptr<PipeTransport> PipeTransport::create_for_coupler(
    const std::filesystem::path& directory, std::chrono::microseconds busy_wait) {
  if (!std::filesystem::is_directory(directory))
    throw TransportError("channel directory " + directory.string() + " does not exist");
  ignore_sigpipe();
  std::unique_ptr<PipeTransport> transport(new PipeTransport(directory / kFromSolverFifo,
                                                             directory / kToSolverFifo, "solver",
                                                             /*owns_fifos=*/true, busy_wait));
  make_fifo(transport->write_path_);
  make_fifo(transport->read_path_);
  transport->open_read_end();
  return transport;
}

std::unique_ptr<PipeTransport> PipeTransport::open_for_solver(
    const std::filesystem::path& directory, double timeout_seconds,
    const AliveCheck& still_alive_check, std::chrono::microseconds busy_wait) {
  ignore_sigpipe();
  std::unique_ptr<PipeTransport> transport(new PipeTransport(directory / kToSolverFifo,
                                                             directory / kFromSolverFifo, "coupler",
                                                             /*owns_fifos=*/false, busy_wait));
  transport->open_read_end();
  transport->connect(timeout_seconds, still_alive_check);
  return transport;
}

PipeTransport::~PipeTransport() {
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
    throw TransportError("no named pipe " + read_path_.string() + " (is the " + peer() +
                         " running and using the pipe transport?)");
  read_fd_ = ::open(read_path_.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (read_fd_ < 0)
    throw TransportError(system_error_text("cannot open " + read_path_.string(), errno));
}

ChannelAddress PipeTransport::address() const {
  return {TransportKind::kPipe, read_path_.parent_path().string(), ""};
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
      throw TransportTimeout("the " + peer() + " did not open " + write_path_.string() +
                             " within " + seconds_text(timeout_seconds));
    if (still_alive_check) still_alive_check();
    std::this_thread::sleep_for(std::min(pause, deadline.next_slice()));
    pause = std::min(pause * 2, std::chrono::milliseconds(50));
  }
}

}  // namespace cocopp::protocol
