#include "core/protocol/transport.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "core/protocol/file_transport.hpp"
#include "core/protocol/pipe_transport.hpp"
#include "core/protocol/tcp_transport.hpp"

namespace cocopp::protocol {

TransportKind parse_transport_kind(const std::string& name) {
  if (name == "pipe") return TransportKind::kPipe;
  if (name == "file") return TransportKind::kFile;
  if (name == "tcp") return TransportKind::kTcp;
  throw std::invalid_argument("unknown transport '" + name + "' (use pipe, file or tcp)");
}

std::string transport_name(TransportKind kind) {
  switch (kind) {
    case TransportKind::kPipe:
      return "pipe";
    case TransportKind::kFile:
      return "file";
    case TransportKind::kTcp:
      return "tcp";
  }
  return "?";
}

std::vector<std::pair<std::string, std::string>> solver_environment(const ChannelAddress& address) {
  std::vector<std::pair<std::string, std::string>> variables = {
      {kTransportVariable, transport_name(address.kind)}, {kChannelVariable, address.channel}};
  if (address.kind == TransportKind::kTcp) variables.emplace_back(kTokenVariable, address.token);
  return variables;
}

bool channel_in_environment() {
  const auto given = [](const char* name) {
    const char* value = std::getenv(name);
    return value != nullptr && *value != '\0';
  };
  return given(kChannelFileVariable) || (given(kTransportVariable) && given(kChannelVariable));
}

namespace {

/// The VARIABLE=value lines of a channel file.
std::map<std::string, std::string> read_channel_file(const std::string& path) {
  std::ifstream in(path);
  if (!in)
    throw TransportError(std::string(kChannelFileVariable) + "=" + path +
                         ": cannot read the file (is the coupler running and waiting for this "
                         "solver? it writes the file when it starts)");
  std::map<std::string, std::string> values;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    const auto equals = line.find('=');
    if (equals == std::string::npos)
      throw TransportError(path + ": '" + line + "' is not VARIABLE=value");
    values[line.substr(0, equals)] = line.substr(equals + 1);
  }
  return values;
}

}  // namespace

void write_channel_file(const std::filesystem::path& file, const ChannelAddress& address,
                        const std::string& solver_name) {
  const std::filesystem::path partial = file.string() + ".partial";
  std::error_code ignored;
  std::filesystem::remove(partial, ignored);
  // Created readable by the user only, before the secret goes in.
  const int fd = ::open(partial.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0)
    throw TransportError("cannot write the channel file " + partial.string() + ": " +
                         std::strerror(errno));
  std::string text = "# cocopp: the channel of solver '" + solver_name +
                     "'. Start the solver with " + kChannelFileVariable + "=" + file.string() +
                     "\n# in its environment (docs/clusters.md); removed once it has connected.\n";
  for (const auto& [variable, value] : solver_environment(address))
    text += variable + "=" + value + "\n";
  const bool written = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  ::close(fd);
  if (!written || ::rename(partial.c_str(), file.c_str()) != 0) {
    std::filesystem::remove(partial, ignored);
    throw TransportError("cannot write the channel file " + file.string());
  }
}

ChannelAddress channel_from_environment() {
  const char* file = std::getenv(kChannelFileVariable);
  const bool in_file = file != nullptr && *file != '\0';
  std::map<std::string, std::string> from_file;
  if (in_file) from_file = read_channel_file(file);
  const auto variable = [&](const char* name) -> std::string {
    if (in_file) {
      const auto found = from_file.find(name);
      if (found == from_file.end() || found->second.empty())
        throw TransportError(std::string(file) + " has no " + name);
      return found->second;
    }
    const char* value = std::getenv(name);
    if (value == nullptr || *value == '\0') throw TransportError(std::string(name) + " is not set");
    return value;
  };
  ChannelAddress address;
  const std::string kind = variable(kTransportVariable);
  try {
    address.kind = parse_transport_kind(kind);
  } catch (const std::invalid_argument& e) {
    throw TransportError(std::string(kTransportVariable) + ": " + e.what());
  }
  address.channel = variable(kChannelVariable);
  if (address.kind == TransportKind::kTcp) address.token = variable(kTokenVariable);
  return address;
}

std::unique_ptr<Transport> create_coupler_channel(const CouplerChannelOptions& options) {
  switch (options.kind) {
    case TransportKind::kPipe:
      return PipeTransport::create_for_coupler(options.directory, options.busy_wait);
    case TransportKind::kFile:
      return FileTransport::create_for_coupler(options.directory);
    case TransportKind::kTcp:
      return TcpTransport::listen(options.host, options.port, options.busy_wait);
  }
  throw TransportError("unknown transport");
}

std::unique_ptr<Transport> create_coupler_channel(TransportKind kind,
                                                  const std::filesystem::path& directory,
                                                  std::chrono::microseconds busy_wait) {
  CouplerChannelOptions options;
  options.kind = kind;
  options.directory = directory;
  options.busy_wait = busy_wait;
  return create_coupler_channel(options);
}

std::unique_ptr<Transport> open_solver_channel(const ChannelAddress& address,
                                               double timeout_seconds,
                                               const AliveCheck& still_alive_check,
                                               std::chrono::microseconds busy_wait) {
  switch (address.kind) {
    case TransportKind::kPipe:
      return PipeTransport::open_for_solver(address.channel, timeout_seconds, still_alive_check,
                                            busy_wait);
    case TransportKind::kFile:
      return FileTransport::open_for_solver(address.channel);
    case TransportKind::kTcp:
      return TcpTransport::connect_to(address.channel, address.token, timeout_seconds,
                                      still_alive_check, busy_wait);
  }
  throw TransportError("unknown transport");
}

std::unique_ptr<Transport> open_solver_channel(TransportKind kind,
                                               const std::filesystem::path& directory,
                                               double timeout_seconds,
                                               const AliveCheck& still_alive_check,
                                               std::chrono::microseconds busy_wait) {
  return open_solver_channel({kind, directory.string(), ""}, timeout_seconds, still_alive_check,
                             busy_wait);
}

std::chrono::microseconds busy_wait_from_environment() {
  const char* text = std::getenv(kBusyWaitVariable);
  if (text == nullptr || *text == '\0') return std::chrono::microseconds(0);
  char* end = nullptr;
  const double seconds = std::strtod(text, &end);
  if (end == text || *end != '\0' || !(seconds >= 0.0 && seconds <= 0.1))
    throw TransportError(std::string(kBusyWaitVariable) + "='" + text +
                         "' is not a number of seconds in [0, 0.1]");
  return std::chrono::microseconds(std::llround(1e6 * seconds));
}

Deadline::Deadline(double seconds) : forever_(!std::isfinite(seconds)) {
  if (!forever_)
    end_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                              std::chrono::duration<double>(std::max(seconds, 0.0)));
}

bool Deadline::expired() const {
  return !forever_ && Clock::now() >= end_;
}

std::chrono::milliseconds Deadline::next_slice() const {
  if (forever_) return kAliveCheckInterval;
  const auto remaining = std::chrono::ceil<std::chrono::milliseconds>(end_ - Clock::now());
  return std::clamp(remaining, std::chrono::milliseconds(0), kAliveCheckInterval);
}

void Transport::check_payload_size(std::size_t bytes) const {
  if (bytes > max_payload_)
    throw ProtocolError("a frame of " + std::to_string(bytes) +
                        " bytes was announced; the largest this channel takes now is " +
                        std::to_string(max_payload_) + " bytes (corrupt stream?)");
}

std::string seconds_text(double seconds) {
  std::ostringstream out;
  out << seconds << " s";
  return out.str();
}

}  // namespace cocopp::protocol
