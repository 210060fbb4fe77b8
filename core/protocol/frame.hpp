#pragma once
// Binary frames of the cocopp solver protocol (docs/protocol.md has the byte-level layout).
//
// A frame is one message: its payload starts with a u8 message type, followed by the
// message's fields. On the wire (pipe, or message file) a frame is preceded by its payload
// length as a u32. All numbers are little-endian and doubles are raw IEEE 754 binary64, so
// values cross the channel bit for bit (NaN and infinities included) and nothing is formatted
// as text.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace cocopp::protocol {

/// One message's payload (type byte first), without the length prefix.
using Frame = std::vector<std::uint8_t>;

/// A malformed, truncated or unexpected message.
class ProtocolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bytes of the length prefix that precedes each frame on the wire.
constexpr std::size_t kLengthPrefixBytes = 4;
/// Largest payload accepted: a garbage length must not make the reader allocate gigabytes.
constexpr std::uint32_t kMaxPayloadBytes = 1u << 30;

/// Appends fields to a frame, little-endian.
class FrameWriter {
 public:
  FrameWriter& u8(std::uint8_t value);
  FrameWriter& u32(std::uint32_t value);
  FrameWriter& u64(std::uint64_t value);
  FrameWriter& i32(std::int32_t value);
  FrameWriter& i64(std::int64_t value);
  FrameWriter& f64(double value);
  /// u32 byte count, then the bytes (UTF-8 by convention, not checked).
  FrameWriter& string(const std::string& value);
  /// u64 count, then `count` raw doubles.
  FrameWriter& f64_array(const double* values, std::size_t count);
  FrameWriter& f64_array(const std::vector<double>& values);
  /// u64 count, then `count` i64.
  FrameWriter& i64_array(const std::vector<std::int64_t>& values);

  const Frame& frame() const { return frame_; }
  Frame take() { return std::move(frame_); }

 private:
  Frame frame_;
};

/// Reads fields from a frame in order; throws ProtocolError when the frame is too short.
/// The frame must outlive the reader.
class FrameReader {
 public:
  explicit FrameReader(const Frame& frame) : data_(frame.data()), size_(frame.size()) {}

  std::uint8_t u8();
  std::uint32_t u32();
  std::uint64_t u64();
  std::int32_t i32();
  std::int64_t i64();
  double f64();
  std::string string();
  std::vector<double> f64_array();
  std::vector<std::int64_t> i64_array();

  std::size_t remaining() const { return size_ - offset_; }
  /// Throws ProtocolError if bytes are left over (a message longer than its layout).
  void expect_end() const;

 private:
  const std::uint8_t* take(std::size_t bytes, const char* what);
  std::size_t array_count(std::size_t element_bytes, const char* what);

  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t offset_ = 0;
};

/// The 4-byte little-endian length prefix of a frame.
void encode_length_prefix(std::size_t payload_bytes, std::uint8_t* prefix);
/// The payload length in a prefix; throws ProtocolError for 0 or more than kMaxPayloadBytes.
std::uint32_t decode_length_prefix(const std::uint8_t* prefix);

/// Prefix + payload: the bytes of a message file.
std::vector<std::uint8_t> with_length_prefix(const Frame& frame);
/// The inverse; throws ProtocolError on truncated input or trailing bytes.
Frame strip_length_prefix(const std::vector<std::uint8_t>& bytes);

}  // namespace cocopp::protocol
