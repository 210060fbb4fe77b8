#pragma once
// Frames over a pair of file descriptors: the part of a transport that is the same for named
// pipes and for a TCP connection. Every read and write goes through poll() in slices of at
// most 100 ms, so that the alive check runs; a receive first reads for up to `busy_wait`
// without sleeping (see receive()).
#include <chrono>
#include <string>

#include "core/protocol/transport.hpp"

namespace cocopp::protocol {

class StreamTransport : public Transport {
 public:
  ~StreamTransport() override;
  StreamTransport(const StreamTransport&) = delete;
  StreamTransport& operator=(const StreamTransport&) = delete;

  using Transport::send;
  void send(const Frame& frame, double timeout_seconds,
            const AliveCheck& still_alive_check) override;
  /// Waits for the next frame. For up to `busy_wait` it reads without sleeping: a message that
  /// comes within it costs no process wake-up (about 50 us on a loaded machine), which on a
  /// fast solver is most of a coupling iteration; a slower one costs at most `busy_wait` of
  /// CPU. Between reads it yields its core, which a process with work may need: with fewer
  /// cores than processes a spin that did not yield slowed the tube run tenfold.
  Frame receive(double timeout_seconds, const AliveCheck& still_alive_check) override;

 protected:
  /// `peer`: "solver" or "coupler", for messages.
  StreamTransport(std::string peer, std::chrono::microseconds busy_wait)
      : peer_(std::move(peer)), busy_wait_(busy_wait) {}

  /// Wait until `fd` is ready for `events` (or hung up); throws TransportTimeout.
  void wait_for(int fd, short events, const Deadline& deadline, const AliveCheck& check,
                const char* activity) const;
  /// Throws the exception a failed read or write of errno `error` on `what` means.
  [[noreturn]] void fail_io(const std::string& what, int error) const;

  const std::string& peer() const { return peer_; }
  /// Descriptors the derived class opens (the same one twice for a socket); closed here.
  int read_fd_ = -1;
  int write_fd_ = -1;
  std::string read_name_;          ///< for messages: the FIFO's path, the peer's address
  std::string write_name_;         ///< the same for the write end
  std::string link_ = "the pipe";  ///< what the peer closes: "the pipe", "the connection"
  /// The writer has connected: read() returning 0 now means EOF (a FIFO returns 0 before).
  bool has_read_ = false;

  void read_exactly(std::uint8_t* data, std::size_t size, const Deadline& deadline,
                    const AliveCheck& check);
  void write_all(const std::uint8_t* data, std::size_t size, const Deadline& deadline,
                 const AliveCheck& check);

 private:
  std::string peer_;
  std::chrono::microseconds busy_wait_{0};
};

/// "what: strerror(error)".
std::string system_error_text(const std::string& what, int error);

}  // namespace cocopp::protocol
