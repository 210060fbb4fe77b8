#include <gtest/gtest.h>

#include "core/protocol/messages.hpp"

namespace cocopp::protocol {
namespace {

sdk::InterfaceDescription two_part_description() {
  sdk::InterfaceDescription description;
  sdk::ModelPart wall{"wall", {1, 2}, {0, 0, 0, 1, 0, 0}, {"displacement"}, {"pressure"}};
  sdk::ModelPart outlet{"outlet", {7}, {2, 0, 0}, {}, {"traction", "pressure"}};
  description.model_parts = {wall, outlet};
  description.initial_output = {1, 2, 3, 4, 5, 6};
  return description;
}

TEST(MessagesTest, RequestsRoundTrip) {
  const auto run = decode_initialize(encode_initialize({0.001, 12}));
  EXPECT_EQ(run.delta_t, 0.001);
  EXPECT_EQ(run.timestep_start, 12);

  const auto step = decode_initialize_step(encode_initialize_step({13, 0.013}));
  EXPECT_EQ(step.step, 13);
  EXPECT_EQ(step.time, 0.013);

  const std::vector<double> values = {1, -2, 3.5};
  EXPECT_EQ(decode_solve(encode_solve(values.data(), values.size())), values);

  for (auto type : {MessageType::kFinalizeStep, MessageType::kOutputStep, MessageType::kStop,
                    MessageType::kReportConvergence, MessageType::kOk}) {
    const Frame frame = encode_empty(type);
    EXPECT_EQ(frame.size(), 1u);
    EXPECT_EQ(message_type(frame), type);
    EXPECT_NO_THROW(decode_empty(frame, type));
  }
}

TEST(MessagesTest, RepliesRoundTrip) {
  const auto hello = decode_hello(encode_hello({kProtocolVersion, 4242}));
  EXPECT_EQ(hello.version, kProtocolVersion);
  EXPECT_EQ(hello.pid, 4242);

  EXPECT_EQ(decode_data(encode_data({0.5, 0.25})), (std::vector<double>{0.5, 0.25}));
  EXPECT_EQ(decode_error(encode_error("diverged: Courant number 12")),
            "diverged: Courant number 12");
  EXPECT_EQ(decode_rejected(encode_rejected("2 cells inside out")), "2 cells inside out");
  EXPECT_EQ(message_name(message_type(encode_rejected("x"))), "REJECTED");
  for (bool converged : {false, true}) {
    const auto data = decode_data_converged(encode_data_converged({0.5, -1.0}, converged));
    EXPECT_EQ(data.values, (std::vector<double>{0.5, -1.0}));
    EXPECT_EQ(data.converged, converged);
  }

  const auto original = two_part_description();
  const auto decoded = decode_interface(encode_interface(original));
  ASSERT_EQ(decoded.model_parts.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& a = original.model_parts[i];
    const auto& b = decoded.model_parts[i];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.ids, b.ids);
    EXPECT_EQ(a.coordinates, b.coordinates);
    EXPECT_EQ(a.input_variables, b.input_variables);
    EXPECT_EQ(a.output_variables, b.output_variables);
  }
  EXPECT_EQ(decoded.initial_output, original.initial_output);
}

// Names a solver chooses reach the terminal and the results as they are: an escape sequence or
// a bell in one is a protocol error that names it, printably.
TEST(MessagesTest, NamesWithControlCharactersAreRefused) {
  auto description = two_part_description();
  EXPECT_NO_THROW(decode_interface(encode_interface(description)));
  description.model_parts[0].name = "wall\x1b[31m";
  try {
    decode_interface(encode_interface(description));
    ADD_FAILURE() << "no error";
  } catch (const ProtocolError& e) {
    EXPECT_NE(std::string(e.what()).find("the model part name 'wall?[31m' holds a control "
                                         "character (byte 0x1b at position 5)"),
              std::string::npos)
        << e.what();
  }
  description = two_part_description();
  description.model_parts[1].output_variables[0] = "pres\asure";
  try {
    decode_interface(encode_interface(description));
    ADD_FAILURE() << "no error";
  } catch (const ProtocolError& e) {
    EXPECT_NE(std::string(e.what()).find("the variable name 'pres?sure'"), std::string::npos)
        << e.what();
  }
}

TEST(MessagesTest, FirstByteIsTheType) {
  EXPECT_EQ(encode_solve(nullptr, 0)[0], 3);
  EXPECT_EQ(encode_hello({})[0], 128);
  EXPECT_EQ(encode_error("x")[0], 132);
  EXPECT_EQ(encode_rejected("x")[0], 133);
  EXPECT_EQ(encode_data_converged({}, true)[0], 134);
  EXPECT_EQ(encode_empty(MessageType::kReportConvergence)[0], 8);
}

TEST(MessagesTest, AConvergedFlagOtherThanZeroOrOneIsRejected) {
  Frame frame = encode_data_converged({1.0}, true);
  frame.back() = 2;
  try {
    decode_data_converged(frame);
    FAIL() << "no exception";
  } catch (const ProtocolError& e) {
    EXPECT_STREQ(e.what(), "DATA_CONVERGED carries the flag 2; it must be 0 or 1");
  }
}

TEST(MessagesTest, WrongTypeIsAProtocolErrorNamingBoth) {
  try {
    decode_data(encode_empty(MessageType::kOk));
    FAIL() << "no exception";
  } catch (const ProtocolError& e) {
    EXPECT_STREQ(e.what(), "expected DATA, got OK");
  }
}

TEST(MessagesTest, UnknownAndEmptyFramesAreRejected) {
  EXPECT_THROW(message_type(Frame{}), ProtocolError);
  EXPECT_THROW(message_type(Frame{77}), ProtocolError);
  EXPECT_EQ(message_name(static_cast<MessageType>(77)), "unknown message type 77");
}

TEST(MessagesTest, EveryTruncatedInterfaceIsRejected) {
  const Frame full = encode_interface(two_part_description());
  for (std::size_t length = 1; length < full.size(); ++length)
    EXPECT_THROW(decode_interface(Frame(full.begin(), full.begin() + length)), ProtocolError)
        << "cut to " << length << " bytes";
}

TEST(MessagesTest, ExtraBytesAreRejected) {
  Frame frame = encode_initialize_step({1, 0.1});
  frame.push_back(0);
  EXPECT_THROW(decode_initialize_step(frame), ProtocolError);
}

}  // namespace
}  // namespace cocopp::protocol
