#include "core/protocol/messages.hpp"

#include <algorithm>
#include <cstdio>

namespace cocopp::protocol {

namespace {

FrameWriter start(MessageType type) {
  FrameWriter writer;
  writer.u8(static_cast<std::uint8_t>(type));
  return writer;
}

/// A reader positioned after the type byte, which must be `expected`.
FrameReader open(const Frame& frame, MessageType expected) {
  const MessageType type = message_type(frame);
  if (type != expected)
    throw ProtocolError("expected " + message_name(expected) + ", got " + message_name(type));
  FrameReader reader(frame);
  reader.u8();
  return reader;
}

void write_names(FrameWriter& writer, const std::vector<std::string>& names) {
  writer.u32(static_cast<std::uint32_t>(names.size()));
  for (const auto& name : names) writer.string(name);
}

/// A name a solver chose (model part, variable) reaches the terminal, the log and the results
/// file as it is: one with a control character (an escape sequence, a bell) is refused.
std::string printable_name(std::string name, const char* what) {
  for (std::size_t i = 0; i < name.size(); ++i) {
    const auto byte = static_cast<unsigned char>(name[i]);
    if (byte >= 0x20 && byte != 0x7f) continue;
    char code[8];
    std::snprintf(code, sizeof code, "0x%02x", byte);
    throw ProtocolError(std::string("INTERFACE: the ") + what + " name '" + printable_text(name) +
                        "' holds a control character (byte " + code + " at position " +
                        std::to_string(i + 1) +
                        "): names are printed and written to the "
                        "results as they are; send printable names");
  }
  return name;
}

std::vector<std::string> read_names(FrameReader& reader) {
  const std::uint32_t count = reader.u32();
  // Every string takes at least its 4-byte length: bounds the reservation by the frame size.
  if (count > reader.remaining() / 4)
    throw ProtocolError("truncated frame: " + std::to_string(count) + " names announced");
  std::vector<std::string> names;
  names.reserve(count);
  for (std::uint32_t i = 0; i < count; ++i)
    names.push_back(printable_name(reader.string(), "variable"));
  return names;
}

}  // namespace

std::string message_name(MessageType type) {
  switch (type) {
    case MessageType::kInitialize:
      return "INITIALIZE";
    case MessageType::kInitializeStep:
      return "INITIALIZE_STEP";
    case MessageType::kSolve:
      return "SOLVE";
    case MessageType::kFinalizeStep:
      return "FINALIZE_STEP";
    case MessageType::kOutputStep:
      return "OUTPUT_STEP";
    case MessageType::kStop:
      return "STOP";
    case MessageType::kSaveRestart:
      return "SAVE_RESTART";
    case MessageType::kReportConvergence:
      return "REPORT_CONVERGENCE";
    case MessageType::kSubsteps:
      return "SUBSTEPS";
    case MessageType::kHello:
      return "HELLO";
    case MessageType::kOk:
      return "OK";
    case MessageType::kInterface:
      return "INTERFACE";
    case MessageType::kData:
      return "DATA";
    case MessageType::kError:
      return "ERROR";
    case MessageType::kRejected:
      return "REJECTED";
    case MessageType::kDataConverged:
      return "DATA_CONVERGED";
  }
  return "unknown message type " + std::to_string(static_cast<int>(type));
}

MessageType message_type(const Frame& frame) {
  if (frame.empty()) throw ProtocolError("empty frame");
  const auto type = static_cast<MessageType>(frame[0]);
  if (message_name(type).rfind("unknown", 0) == 0) throw ProtocolError(message_name(type));
  return type;
}

Frame encode_initialize(const sdk::RunInfo& run) {
  return start(MessageType::kInitialize).f64(run.delta_t).i32(run.timestep_start).take();
}

Frame encode_initialize_step(const StepInfo& step) {
  return start(MessageType::kInitializeStep).i32(step.step).f64(step.time).take();
}

Frame encode_solve(const double* values, std::size_t count) {
  return start(MessageType::kSolve).f64_array(values, count).take();
}

Frame encode_save_restart(std::int32_t step) {
  return start(MessageType::kSaveRestart).i32(step).take();
}

Frame encode_substeps(std::uint32_t substeps) {
  return start(MessageType::kSubsteps).u32(substeps).take();
}

Frame encode_empty(MessageType type) {
  return start(type).take();
}

Frame encode_hello(const Hello& hello) {
  return start(MessageType::kHello).u32(hello.version).i64(hello.pid).take();
}

Frame encode_interface(const sdk::InterfaceDescription& description) {
  FrameWriter writer = start(MessageType::kInterface);
  writer.u32(static_cast<std::uint32_t>(description.model_parts.size()));
  for (const auto& part : description.model_parts) {
    writer.string(part.name).i64_array(part.ids).f64_array(part.coordinates);
    write_names(writer, part.input_variables);
    write_names(writer, part.output_variables);
  }
  writer.f64_array(description.initial_output);
  return writer.take();
}

Frame encode_data(const std::vector<double>& values) {
  return start(MessageType::kData).f64_array(values).take();
}

Frame encode_data_converged(const std::vector<double>& values, bool converged) {
  return start(MessageType::kDataConverged).f64_array(values).u8(converged ? 1 : 0).take();
}

Frame encode_error(const std::string& message) {
  return start(MessageType::kError).string(message).take();
}

Frame encode_rejected(const std::string& message) {
  return start(MessageType::kRejected).string(message).take();
}

sdk::RunInfo decode_initialize(const Frame& frame) {
  FrameReader reader = open(frame, MessageType::kInitialize);
  sdk::RunInfo run;
  run.delta_t = reader.f64();
  run.timestep_start = reader.i32();
  reader.expect_end();
  return run;
}

StepInfo decode_initialize_step(const Frame& frame) {
  FrameReader reader = open(frame, MessageType::kInitializeStep);
  StepInfo step;
  step.step = reader.i32();
  step.time = reader.f64();
  reader.expect_end();
  return step;
}

std::vector<double> decode_solve(const Frame& frame) {
  FrameReader reader = open(frame, MessageType::kSolve);
  auto values = reader.f64_array();
  reader.expect_end();
  return values;
}

std::int32_t decode_save_restart(const Frame& frame) {
  FrameReader reader = open(frame, MessageType::kSaveRestart);
  const std::int32_t step = reader.i32();
  reader.expect_end();
  return step;
}

std::uint32_t decode_substeps(const Frame& frame) {
  FrameReader reader = open(frame, MessageType::kSubsteps);
  const std::uint32_t substeps = reader.u32();
  reader.expect_end();
  if (substeps == 0) throw ProtocolError("SUBSTEPS of 0: a window has at least one substep");
  return substeps;
}

void decode_empty(const Frame& frame, MessageType expected) {
  open(frame, expected).expect_end();
}

Hello decode_hello(const Frame& frame) {
  FrameReader reader = open(frame, MessageType::kHello);
  Hello hello;
  hello.version = reader.u32();
  hello.pid = reader.i64();
  reader.expect_end();
  return hello;
}

sdk::InterfaceDescription decode_interface(const Frame& frame) {
  FrameReader reader = open(frame, MessageType::kInterface);
  sdk::InterfaceDescription description;
  const std::uint32_t parts = reader.u32();
  for (std::uint32_t i = 0; i < parts; ++i) {
    sdk::ModelPart part;
    part.name = printable_name(reader.string(), "model part");
    part.ids = reader.i64_array();
    part.coordinates = reader.f64_array();
    part.input_variables = read_names(reader);
    part.output_variables = read_names(reader);
    description.model_parts.push_back(std::move(part));
  }
  description.initial_output = reader.f64_array();
  reader.expect_end();
  return description;
}

std::vector<double> decode_data(const Frame& frame) {
  FrameReader reader = open(frame, MessageType::kData);
  auto values = reader.f64_array();
  reader.expect_end();
  return values;
}

DataConverged decode_data_converged(const Frame& frame) {
  FrameReader reader = open(frame, MessageType::kDataConverged);
  DataConverged data;
  data.values = reader.f64_array();
  const std::uint8_t flag = reader.u8();
  if (flag > 1)
    throw ProtocolError("DATA_CONVERGED carries the flag " + std::to_string(flag) +
                        "; it must be 0 or 1");
  data.converged = flag == 1;
  reader.expect_end();
  return data;
}

namespace {
std::string decode_text(const Frame& frame, MessageType type) {
  FrameReader reader = open(frame, type);
  auto message = reader.string();
  reader.expect_end();
  return message;
}
}  // namespace

std::string printable_text(const std::string& text, std::size_t max_bytes) {
  std::string out = text.substr(0, std::min(text.size(), max_bytes));
  for (char& c : out) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && c != '\n' && c != '\t') || byte == 0x7f) c = '?';
  }
  if (text.size() > max_bytes)
    out += "... [" + std::to_string(text.size() - max_bytes) + " more bytes]";
  return out;
}

std::string decode_error(const Frame& frame) {
  return decode_text(frame, MessageType::kError);
}

std::string decode_rejected(const Frame& frame) {
  return decode_text(frame, MessageType::kRejected);
}

}  // namespace cocopp::protocol
