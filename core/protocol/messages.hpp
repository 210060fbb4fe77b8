#pragma once
// The messages of the cocopp solver protocol: coupler requests and solver replies, each
// encoded into and decoded from one Frame. docs/protocol.md describes every payload.
//
// The solver-side data types (InterfaceDescription, RunInfo) are plain structs of the standard
// library in interface_description.hpp, shared by the protocol and the SDK above it.
#include <cstdint>
#include <string>
#include <vector>

#include "core/protocol/frame.hpp"
#include "core/protocol/interface_description.hpp"

namespace cocopp::protocol {

/// Incremented on any incompatible change of a payload; HELLO carries it.
constexpr std::uint32_t kProtocolVersion = 1;

/// The first byte of every frame. Requests (coupler -> solver) are below 128, replies and the
/// solver's HELLO (solver -> coupler) are 128 and up, so a misdirected frame is easy to spot.
enum class MessageType : std::uint8_t {
  kInitialize = 1,
  kInitializeStep = 2,
  kSolve = 3,
  kFinalizeStep = 4,
  kOutputStep = 5,
  kStop = 6,
  kSaveRestart = 7,
  kReportConvergence = 8,
  kSubsteps = 9,
  kHello = 128,
  kOk = 129,
  kInterface = 130,
  kData = 131,
  kError = 132,
  kRejected = 133,
  kDataConverged = 134,
};

/// "SOLVE", "INTERFACE", ...; "unknown message type 7" for anything else.
std::string message_name(MessageType type);
/// The type byte of a frame; throws ProtocolError for an empty frame or an unknown type.
MessageType message_type(const Frame& frame);

struct Hello {
  std::uint32_t version = kProtocolVersion;
  std::int64_t pid = 0;  ///< the process that talks to the coupler (rank 0 under mpirun)
};

struct StepInfo {
  std::int32_t step = 0;
  double time = 0.0;
};

// Coupler -> solver.
Frame encode_initialize(const sdk::RunInfo& run);
Frame encode_initialize_step(const StepInfo& step);
Frame encode_solve(const double* values, std::size_t count);
/// SAVE_RESTART: write what the solver needs to restart after `step`, the step it finalized last.
Frame encode_save_restart(std::int32_t step);
/// SUBSTEPS: the solver takes `substeps` steps of delta_t / substeps per coupling time step
/// (a window); SOLVE then carries the input at each substep's end, DATA the output at each.
/// Sent first, before INITIALIZE, only when the case asks for substeps.
Frame encode_substeps(std::uint32_t substeps);
/// A message without fields: FINALIZE_STEP, OUTPUT_STEP, STOP, REPORT_CONVERGENCE (from now on
/// answer SOLVE with DATA_CONVERGED; sent once, before the first step, only when the case's
/// criterion needs it), or the reply OK.
Frame encode_empty(MessageType type);

// Solver -> coupler.
Frame encode_hello(const Hello& hello);
Frame encode_interface(const sdk::InterfaceDescription& description);
Frame encode_data(const std::vector<double>& values);
Frame encode_error(const std::string& message);
/// The reply to SOLVE after REPORT_CONVERGENCE: the output and whether the solver's own
/// iterations (Newton, PIMPLE's outer loop) converged at their first iteration.
Frame encode_data_converged(const std::vector<double>& values, bool converged);
/// The reply to SOLVE of a solver that cannot solve the step for this input but keeps the
/// step's start and serves on: the coupler may retry with another input.
Frame encode_rejected(const std::string& message);

// Decoding checks the type byte and that the frame holds exactly the message's fields.
sdk::RunInfo decode_initialize(const Frame& frame);
StepInfo decode_initialize_step(const Frame& frame);
std::vector<double> decode_solve(const Frame& frame);
std::int32_t decode_save_restart(const Frame& frame);
/// SUBSTEPS; throws ProtocolError for 0.
std::uint32_t decode_substeps(const Frame& frame);
void decode_empty(const Frame& frame, MessageType expected);
Hello decode_hello(const Frame& frame);
sdk::InterfaceDescription decode_interface(const Frame& frame);
std::vector<double> decode_data(const Frame& frame);
struct DataConverged {
  std::vector<double> values;
  bool converged = false;
};
/// DATA_CONVERGED; the flag byte must be 0 or 1.
DataConverged decode_data_converged(const Frame& frame);
std::string decode_error(const Frame& frame);
/// Longest ERROR or REJECTED text a solver may send once the interface is known (bytes).
constexpr std::size_t kMaxReceivedText = 64 * 1024;
/// A solver's text as it may reach a terminal and a results file: control characters (other
/// than newline and tab) replaced by '?', so that no escape sequence reaches the terminal,
/// and cut after `max_bytes` with a note of how much was left out.
std::string printable_text(const std::string& text, std::size_t max_bytes = 4096);
std::string decode_rejected(const Frame& frame);

}  // namespace cocopp::protocol
