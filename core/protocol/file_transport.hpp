#pragma once
// A transport for solvers that can only read and write files: every message is one file in
// the channel directory,
//
//   to_solver_00000001.msg, to_solver_00000002.msg, ...      requests, coupler -> solver
//   from_solver_00000001.msg, from_solver_00000002.msg, ...  replies,  solver -> coupler
//
// holding the frame with its length prefix, exactly the bytes the pipe transport would send.
// Each direction numbers its messages from 1. The writer writes `<name>.tmp` and renames it
// to `<name>.msg`: the rename is atomic, so the appearance of the .msg file is the ready
// marker and a reader never sees a half-written message. The reader polls for the next
// expected name (every 1 ms, backing off to 20 ms), reads the file and deletes it.
//
// The coupler removes stale message files when it creates the channel and leftovers when the
// transport is destroyed.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "core/protocol/transport.hpp"

namespace cocopp::protocol {

class FileTransport final : public Transport {
 public:
  static constexpr const char* kToSolverPrefix = "to_solver_";
  static constexpr const char* kFromSolverPrefix = "from_solver_";

  static std::unique_ptr<FileTransport> create_for_coupler(const std::filesystem::path& directory);
  static std::unique_ptr<FileTransport> open_for_solver(const std::filesystem::path& directory);

  ~FileTransport() override;
  FileTransport(const FileTransport&) = delete;
  FileTransport& operator=(const FileTransport&) = delete;

  /// Nothing to wait for: the first message file is the connection.
  void connect(double, const AliveCheck&) override {}
  ChannelAddress address() const override {
    return {TransportKind::kFile, directory_.string(), ""};
  }
  using Transport::send;
  void send(const Frame& frame, double timeout_seconds,
            const AliveCheck& still_alive_check) override;
  Frame receive(double timeout_seconds, const AliveCheck& still_alive_check) override;

  /// "to_solver_00000012.msg"
  static std::string message_file_name(const std::string& prefix, std::uint64_t sequence,
                                       const char* extension = ".msg");
  /// Remove every message file (and half-written .tmp) of a channel.
  static void remove_message_files(const std::filesystem::path& directory);

 private:
  FileTransport(std::filesystem::path directory, std::string outgoing_prefix,
                std::string incoming_prefix, std::string peer, bool owns_files);

  std::filesystem::path directory_;
  std::string outgoing_prefix_;
  std::string incoming_prefix_;
  std::string peer_;
  bool owns_files_;
  std::uint64_t next_outgoing_ = 1;
  std::uint64_t next_incoming_ = 1;
};

}  // namespace cocopp::protocol
