// Fuzz target: protocol frames and messages as a solver could send them (and as the SDK reads
// the coupler's). Every frame is decoded as the message its type byte names; a frame that
// decodes must encode back to the same bytes (the decoder takes nothing it would not write).
#include <cstdint>
#include <cstdlib>

#include "core/protocol/messages.hpp"

namespace {

using namespace cocopp::protocol;

void expect_same(const Frame& encoded, const Frame& frame) {
  if (encoded != frame) std::abort();  // a decoder that accepts what no encoder writes
}

void decode_as_its_type(const Frame& frame) {
  switch (message_type(frame)) {
    case MessageType::kInitialize:
      return expect_same(encode_initialize(decode_initialize(frame)), frame);
    case MessageType::kInitializeStep:
      return expect_same(encode_initialize_step(decode_initialize_step(frame)), frame);
    case MessageType::kSolve: {
      const auto values = decode_solve(frame);
      return expect_same(encode_solve(values.data(), values.size()), frame);
    }
    case MessageType::kSaveRestart:
      return expect_same(encode_save_restart(decode_save_restart(frame)), frame);
    case MessageType::kSubsteps:
      return expect_same(encode_substeps(decode_substeps(frame)), frame);
    case MessageType::kFinalizeStep:
    case MessageType::kOutputStep:
    case MessageType::kStop:
    case MessageType::kReportConvergence:
    case MessageType::kOk:
      decode_empty(frame, message_type(frame));
      return expect_same(encode_empty(message_type(frame)), frame);
    case MessageType::kHello:
      return expect_same(encode_hello(decode_hello(frame)), frame);
    case MessageType::kInterface:
      return expect_same(encode_interface(decode_interface(frame)), frame);
    case MessageType::kData:
      return expect_same(encode_data(decode_data(frame)), frame);
    case MessageType::kDataConverged: {
      const auto data = decode_data_converged(frame);
      return expect_same(encode_data_converged(data.values, data.converged), frame);
    }
    case MessageType::kError:
      (void)printable_text(decode_error(frame));
      return;
    case MessageType::kRejected:
      (void)printable_text(decode_rejected(frame));
      return;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const Frame bytes(data, data + size);
  try {
    if (size >= kLengthPrefixBytes) (void)decode_length_prefix(data);
    (void)strip_length_prefix(bytes);
  } catch (const ProtocolError&) {
  }
  try {
    decode_as_its_type(bytes);
  } catch (const ProtocolError&) {
    // a clean error: the coupler reports the solver's malformed message
  }
  return 0;
}
