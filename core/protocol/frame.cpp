#include "core/protocol/frame.hpp"

#include <cstring>

namespace cocopp::protocol {

namespace {

// Bulk-copying arrays is only valid when the host byte order is the wire byte order.
constexpr bool kHostIsLittleEndian = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__;

template <class Unsigned>
void append_little_endian(Frame& out, Unsigned value) {
  for (std::size_t i = 0; i < sizeof(Unsigned); ++i)
    out.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}

template <class Unsigned>
Unsigned load_little_endian(const std::uint8_t* bytes) {
  Unsigned value = 0;
  for (std::size_t i = 0; i < sizeof(Unsigned); ++i)
    value |= static_cast<Unsigned>(bytes[i]) << (8 * i);
  return value;
}

std::uint64_t bits_of(double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

double double_of(std::uint64_t bits) {
  double value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

// Arrays of 8-byte numbers: one memcpy on little-endian hosts, element by element otherwise.
template <class Element>
void append_array(Frame& out, const Element* values, std::size_t count) {
  static_assert(sizeof(Element) == 8);
  if constexpr (kHostIsLittleEndian) {
    const std::size_t start = out.size();
    out.resize(start + count * 8);
    if (count > 0) std::memcpy(out.data() + start, values, count * 8);
  } else {
    for (std::size_t i = 0; i < count; ++i) {
      std::uint64_t bits;
      std::memcpy(&bits, &values[i], 8);
      append_little_endian(out, bits);
    }
  }
}

template <class Element>
std::vector<Element> load_array(const std::uint8_t* bytes, std::size_t count) {
  std::vector<Element> values(count);
  if constexpr (kHostIsLittleEndian) {
    if (count > 0) std::memcpy(values.data(), bytes, count * 8);
  } else {
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint64_t bits = load_little_endian<std::uint64_t>(bytes + 8 * i);
      std::memcpy(&values[i], &bits, 8);
    }
  }
  return values;
}

}  // namespace

FrameWriter& FrameWriter::u8(std::uint8_t value) {
  frame_.push_back(value);
  return *this;
}

FrameWriter& FrameWriter::u32(std::uint32_t value) {
  append_little_endian(frame_, value);
  return *this;
}

FrameWriter& FrameWriter::u64(std::uint64_t value) {
  append_little_endian(frame_, value);
  return *this;
}

FrameWriter& FrameWriter::i32(std::int32_t value) {
  return u32(static_cast<std::uint32_t>(value));
}

FrameWriter& FrameWriter::i64(std::int64_t value) {
  return u64(static_cast<std::uint64_t>(value));
}

FrameWriter& FrameWriter::f64(double value) {
  return u64(bits_of(value));
}

FrameWriter& FrameWriter::string(const std::string& value) {
  if (value.size() > kMaxPayloadBytes) throw ProtocolError("string too long for a frame");
  u32(static_cast<std::uint32_t>(value.size()));
  frame_.insert(frame_.end(), value.begin(), value.end());
  return *this;
}

FrameWriter& FrameWriter::f64_array(const double* values, std::size_t count) {
  u64(count);
  append_array(frame_, values, count);
  return *this;
}

FrameWriter& FrameWriter::f64_array(const std::vector<double>& values) {
  return f64_array(values.data(), values.size());
}

FrameWriter& FrameWriter::i64_array(const std::vector<std::int64_t>& values) {
  u64(values.size());
  append_array(frame_, values.data(), values.size());
  return *this;
}

const std::uint8_t* FrameReader::take(std::size_t bytes, const char* what) {
  if (bytes > remaining())
    throw ProtocolError("truncated frame: " + std::string(what) + " needs " +
                        std::to_string(bytes) + " bytes at offset " + std::to_string(offset_) +
                        ", only " + std::to_string(remaining()) + " left");
  const std::uint8_t* start = data_ + offset_;
  offset_ += bytes;
  return start;
}

std::uint8_t FrameReader::u8() {
  return *take(1, "u8");
}

std::uint32_t FrameReader::u32() {
  return load_little_endian<std::uint32_t>(take(4, "u32"));
}

std::uint64_t FrameReader::u64() {
  return load_little_endian<std::uint64_t>(take(8, "u64"));
}

std::int32_t FrameReader::i32() {
  return static_cast<std::int32_t>(u32());
}

std::int64_t FrameReader::i64() {
  return static_cast<std::int64_t>(u64());
}

double FrameReader::f64() {
  return double_of(load_little_endian<std::uint64_t>(take(8, "f64")));
}

std::string FrameReader::string() {
  const std::uint32_t length = u32();
  const auto* bytes = take(length, "string");
  return std::string(reinterpret_cast<const char*>(bytes), length);
}

// Checked before allocating, so that a corrupt count cannot allocate more than the frame holds.
std::size_t FrameReader::array_count(std::size_t element_bytes, const char* what) {
  const std::uint64_t count = u64();
  if (count > remaining() / element_bytes)
    throw ProtocolError("truncated frame: " + std::string(what) + " of " + std::to_string(count) +
                        " elements at offset " + std::to_string(offset_) + ", only " +
                        std::to_string(remaining()) + " bytes left");
  return static_cast<std::size_t>(count);
}

std::vector<double> FrameReader::f64_array() {
  const std::size_t count = array_count(8, "f64 array");
  return load_array<double>(take(count * 8, "f64 array"), count);
}

std::vector<std::int64_t> FrameReader::i64_array() {
  const std::size_t count = array_count(8, "i64 array");
  return load_array<std::int64_t>(take(count * 8, "i64 array"), count);
}

void FrameReader::expect_end() const {
  if (remaining() != 0)
    throw ProtocolError("frame has " + std::to_string(remaining()) +
                        " unexpected bytes after its last field");
}

void encode_length_prefix(std::size_t payload_bytes, std::uint8_t* prefix) {
  if (payload_bytes == 0 || payload_bytes > kMaxPayloadBytes)
    throw ProtocolError("cannot send a frame of " + std::to_string(payload_bytes) + " bytes");
  for (std::size_t i = 0; i < kLengthPrefixBytes; ++i)
    prefix[i] = static_cast<std::uint8_t>(payload_bytes >> (8 * i));
}

std::uint32_t decode_length_prefix(const std::uint8_t* prefix) {
  const auto length = load_little_endian<std::uint32_t>(prefix);
  if (length == 0) throw ProtocolError("empty frame (length 0)");
  if (length > kMaxPayloadBytes)
    throw ProtocolError("frame length " + std::to_string(length) + " exceeds the limit of " +
                        std::to_string(kMaxPayloadBytes) + " bytes (corrupt stream?)");
  return length;
}

std::vector<std::uint8_t> with_length_prefix(const Frame& frame) {
  std::vector<std::uint8_t> bytes(kLengthPrefixBytes + frame.size());
  encode_length_prefix(frame.size(), bytes.data());
  std::memcpy(bytes.data() + kLengthPrefixBytes, frame.data(), frame.size());
  return bytes;
}

Frame strip_length_prefix(const std::vector<std::uint8_t>& bytes) {
  if (bytes.size() < kLengthPrefixBytes)
    throw ProtocolError("truncated frame: " + std::to_string(bytes.size()) +
                        " bytes, not even the length prefix");
  const std::uint32_t length = decode_length_prefix(bytes.data());
  const std::size_t present = bytes.size() - kLengthPrefixBytes;
  if (present < length)
    throw ProtocolError("truncated frame: length prefix says " + std::to_string(length) +
                        " bytes, " + std::to_string(present) + " present");
  if (present > length)
    throw ProtocolError("frame followed by " + std::to_string(present - length) +
                        " unexpected bytes");
  return Frame(bytes.begin() + kLengthPrefixBytes, bytes.end());
}

}  // namespace cocopp::protocol
