#include "core/protocol/transport.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/protocol/file_transport.hpp"
#include "core/protocol/pipe_transport.hpp"

namespace cocopp::protocol {

TransportKind parse_transport_kind(const std::string& name) {
  if (name == "pipe") return TransportKind::kPipe;
  if (name == "file") return TransportKind::kFile;
  throw std::invalid_argument("unknown transport '" + name + "' (use pipe or file)");
}

std::string transport_name(TransportKind kind) {
  return kind == TransportKind::kPipe ? "pipe" : "file";
}

std::unique_ptr<Transport> create_coupler_channel(TransportKind kind,
                                                  const std::filesystem::path& directory,
                                                  std::chrono::microseconds busy_wait) {
  if (kind == TransportKind::kPipe) return PipeTransport::create_for_coupler(directory, busy_wait);
  return FileTransport::create_for_coupler(directory);
}

std::unique_ptr<Transport> open_solver_channel(TransportKind kind,
                                               const std::filesystem::path& directory,
                                               double timeout_seconds,
                                               const AliveCheck& still_alive_check,
                                               std::chrono::microseconds busy_wait) {
  if (kind == TransportKind::kPipe)
    return PipeTransport::open_for_solver(directory, timeout_seconds, still_alive_check, busy_wait);
  return FileTransport::open_for_solver(directory);
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
