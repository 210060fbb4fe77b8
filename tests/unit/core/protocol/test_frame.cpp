#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "core/protocol/frame.hpp"

namespace cocopp::protocol {
namespace {

TEST(FrameTest, NumbersAreLittleEndian) {
  FrameWriter writer;
  writer.u32(0x01020304).i32(-2).f64(1.0);
  const Frame expected = {0x04, 0x03, 0x02, 0x01, 0xFE, 0xFF, 0xFF, 0xFF,
                          0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xF0, 0x3F};
  EXPECT_EQ(writer.frame(), expected);
}

TEST(FrameTest, AllFieldTypesRoundTrip) {
  FrameWriter writer;
  writer.u8(7)
      .u32(4000000000u)
      .u64(1ull << 40)
      .i32(-123456)
      .i64(-(1ll << 50))
      .f64(-2.5e-300)
      .string("wall")
      .string("")
      .f64_array({1.5, -2.25, 1e300})
      .f64_array(std::vector<double>{})
      .i64_array({-1, 0, 1ll << 62});
  const Frame frame = writer.take();
  FrameReader reader(frame);
  EXPECT_EQ(reader.u8(), 7);
  EXPECT_EQ(reader.u32(), 4000000000u);
  EXPECT_EQ(reader.u64(), 1ull << 40);
  EXPECT_EQ(reader.i32(), -123456);
  EXPECT_EQ(reader.i64(), -(1ll << 50));
  EXPECT_EQ(reader.f64(), -2.5e-300);
  EXPECT_EQ(reader.string(), "wall");
  EXPECT_EQ(reader.string(), "");
  EXPECT_EQ(reader.f64_array(), (std::vector<double>{1.5, -2.25, 1e300}));
  EXPECT_TRUE(reader.f64_array().empty());
  EXPECT_EQ(reader.i64_array(), (std::vector<std::int64_t>{-1, 0, 1ll << 62}));
  EXPECT_EQ(reader.remaining(), 0u);
  EXPECT_NO_THROW(reader.expect_end());
}

TEST(FrameTest, SpecialDoublesCrossBitForBit) {
  const std::uint64_t nan_with_payload = 0x7FF8000000000123ull;
  double nan;
  std::memcpy(&nan, &nan_with_payload, sizeof nan);
  const std::vector<double> values = {nan, std::numeric_limits<double>::infinity(), -0.0,
                                      std::numeric_limits<double>::denorm_min()};
  const Frame frame = FrameWriter().f64_array(values).take();
  FrameReader reader(frame);
  const auto decoded = reader.f64_array();
  ASSERT_EQ(decoded.size(), values.size());
  EXPECT_EQ(std::memcmp(decoded.data(), values.data(), values.size() * sizeof(double)), 0);
}

TEST(FrameTest, EveryTruncationOfAFrameIsDetected) {
  const Frame full = FrameWriter().u8(3).string("displacement").f64_array({1, 2, 3}).take();
  for (std::size_t length = 0; length < full.size(); ++length) {
    const Frame cut(full.begin(), full.begin() + length);
    FrameReader reader(cut);
    EXPECT_THROW(
        {
          reader.u8();
          reader.string();
          reader.f64_array();
        },
        ProtocolError)
        << "frame cut to " << length << " bytes";
  }
}

TEST(FrameTest, HugeArrayCountIsRejectedBeforeAllocating) {
  const Frame frame = FrameWriter().u64(1ull << 60).f64(1.0).take();
  FrameReader reader(frame);
  try {
    reader.f64_array();
    FAIL() << "no exception";
  } catch (const ProtocolError& e) {
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
}

TEST(FrameTest, TrailingBytesAreDetected) {
  const Frame frame = FrameWriter().u8(1).u8(2).take();
  FrameReader reader(frame);
  reader.u8();
  EXPECT_THROW(reader.expect_end(), ProtocolError);
}

TEST(FrameTest, LengthPrefixRoundTrip) {
  const Frame frame = {1, 2, 3};
  const auto bytes = with_length_prefix(frame);
  EXPECT_EQ(bytes, (std::vector<std::uint8_t>{3, 0, 0, 0, 1, 2, 3}));
  EXPECT_EQ(strip_length_prefix(bytes), frame);
}

TEST(FrameTest, TruncatedOrPaddedWireBytesAreRejected) {
  const auto bytes = with_length_prefix(Frame{1, 2, 3});
  for (std::size_t length = 0; length < bytes.size(); ++length)
    EXPECT_THROW(strip_length_prefix({bytes.begin(), bytes.begin() + length}), ProtocolError)
        << length;
  auto padded = bytes;
  padded.push_back(0);
  EXPECT_THROW(strip_length_prefix(padded), ProtocolError);
}

TEST(FrameTest, ImpossibleLengthsAreRejected) {
  const std::uint8_t zero[4] = {0, 0, 0, 0};
  EXPECT_THROW(decode_length_prefix(zero), ProtocolError);
  const std::uint8_t huge[4] = {0xFF, 0xFF, 0xFF, 0xFF};
  EXPECT_THROW(decode_length_prefix(huge), ProtocolError);
  std::uint8_t prefix[4];
  EXPECT_THROW(encode_length_prefix(0, prefix), ProtocolError);
}

}  // namespace
}  // namespace cocopp::protocol
