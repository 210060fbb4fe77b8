#include "core/protocol/file_transport.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <thread>
#include <vector>

namespace cocopp::protocol {

namespace {

std::string system_error_text(const std::string& what, int error) {
  return what + ": " + std::strerror(error);
}

void write_file(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes) {
  // A new file, never through a link planted at the name (it would overwrite the target).
  ::unlink(path.c_str());
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) throw TransportError(system_error_text("cannot create " + path.string(), errno));
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t put = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (put < 0 && errno == EINTR) continue;
    if (put < 0) {
      const int error = errno;
      ::close(fd);
      throw TransportError(system_error_text("cannot write " + path.string(), error));
    }
    written += static_cast<std::size_t>(put);
  }
  ::close(fd);
}

/// The whole file, or false if it does not exist (yet). Only a regular file of at most
/// `max_bytes` is read: opened without blocking and without following a link, so that a FIFO,
/// a device or a link planted at a message's name is an error instead of a wait for ever or a
/// read of another file, and a huge file is refused before it is read.
bool read_file(const std::filesystem::path& path, std::vector<std::uint8_t>& bytes,
               std::size_t max_bytes) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOFOLLOW);
  if (fd < 0) {
    if (errno == ENOENT) return false;
    throw TransportError(system_error_text("cannot open " + path.string(), errno));
  }
  struct stat status {};
  if (::fstat(fd, &status) != 0 || !S_ISREG(status.st_mode)) {
    ::close(fd);
    throw TransportError(path.string() +
                         " is not a regular file (a FIFO, device or other "
                         "file planted at the message's name?)");
  }
  if (static_cast<std::uint64_t>(status.st_size) > max_bytes) {
    ::close(fd);
    throw ProtocolError(path.string() + " holds a frame of " +
                        std::to_string(status.st_size - kLengthPrefixBytes) +
                        " bytes; the largest this channel takes now is " +
                        std::to_string(max_bytes - kLengthPrefixBytes) + " bytes");
  }
  bytes.clear();
  std::uint8_t buffer[1 << 16];
  for (;;) {
    const ssize_t got = ::read(fd, buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      const int error = errno;
      ::close(fd);
      throw TransportError(system_error_text("cannot read " + path.string(), error));
    }
    if (got == 0) break;
    bytes.insert(bytes.end(), buffer, buffer + got);
  }
  ::close(fd);
  return true;
}

bool is_message_file(const std::string& name) {
  const bool ours = name.rfind(FileTransport::kToSolverPrefix, 0) == 0 ||
                    name.rfind(FileTransport::kFromSolverPrefix, 0) == 0;
  const auto dot = name.rfind('.');
  const std::string extension = dot == std::string::npos ? "" : name.substr(dot);
  return ours && (extension == ".msg" || extension == ".tmp");
}

}  // namespace

FileTransport::FileTransport(std::filesystem::path directory, std::string outgoing_prefix,
                             std::string incoming_prefix, std::string peer, bool owns_files)
    : directory_(std::move(directory)),
      outgoing_prefix_(std::move(outgoing_prefix)),
      incoming_prefix_(std::move(incoming_prefix)),
      peer_(std::move(peer)),
      owns_files_(owns_files) {}

std::unique_ptr<FileTransport> FileTransport::create_for_coupler(
    const std::filesystem::path& directory) {
  if (!std::filesystem::is_directory(directory))
    throw TransportError("channel directory " + directory.string() + " does not exist");
  remove_message_files(directory);  // a reply of an earlier run must not be taken for ours
  return std::unique_ptr<FileTransport>(new FileTransport(
      directory, kToSolverPrefix, kFromSolverPrefix, "solver", /*owns_files=*/true));
}

std::unique_ptr<FileTransport> FileTransport::open_for_solver(
    const std::filesystem::path& directory) {
  if (!std::filesystem::is_directory(directory))
    throw TransportError("channel directory " + directory.string() + " does not exist");
  return std::unique_ptr<FileTransport>(new FileTransport(
      directory, kFromSolverPrefix, kToSolverPrefix, "coupler", /*owns_files=*/false));
}

FileTransport::~FileTransport() {
  if (owns_files_) remove_message_files(directory_);
}

std::string FileTransport::message_file_name(const std::string& prefix, std::uint64_t sequence,
                                             const char* extension) {
  char digits[32];
  std::snprintf(digits, sizeof digits, "%08llu", static_cast<unsigned long long>(sequence));
  return prefix + digits + extension;
}

void FileTransport::remove_message_files(const std::filesystem::path& directory) {
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
    if (is_message_file(entry.path().filename().string())) {
      std::error_code ignored;
      std::filesystem::remove(entry.path(), ignored);
    }
  }
}

void FileTransport::send(const Frame& frame, double, const AliveCheck&) {
  const auto temporary = directory_ / message_file_name(outgoing_prefix_, next_outgoing_, ".tmp");
  const auto ready = directory_ / message_file_name(outgoing_prefix_, next_outgoing_, ".msg");
  write_file(temporary, with_length_prefix(frame));
  if (::rename(temporary.c_str(), ready.c_str()) != 0)
    throw TransportError(system_error_text("cannot rename " + temporary.string(), errno));
  ++next_outgoing_;
}

Frame FileTransport::receive(double timeout_seconds, const AliveCheck& still_alive_check) {
  const auto path = directory_ / message_file_name(incoming_prefix_, next_incoming_);
  const Deadline deadline(timeout_seconds);
  auto pause = std::chrono::milliseconds(1);
  std::vector<std::uint8_t> bytes;
  while (!read_file(path, bytes, kLengthPrefixBytes + max_payload())) {
    if (deadline.expired())
      throw TransportTimeout("timed out waiting for " + path.string() + " from the " + peer_);
    if (still_alive_check) still_alive_check();
    std::this_thread::sleep_for(std::min(pause, deadline.next_slice()));
    pause = std::min(pause * 2, std::chrono::milliseconds(20));
  }
  std::filesystem::remove(path);
  ++next_incoming_;
  return strip_length_prefix(bytes);
}

}  // namespace cocopp::protocol
