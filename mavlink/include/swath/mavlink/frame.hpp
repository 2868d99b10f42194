#pragma once
// MAVLink frames: packing a message into a frame, a frame into bytes, and bytes back into frames.
//
// Wire format (MAVLink 2): 0xFD, payload length, incompat flags, compat flags, sequence, system id,
// component id, message id (3 bytes, little endian), payload, checksum (2 bytes, crc.hpp), and a
// 13-byte signature when incompat flag 0x01 is set. MAVLink 1: 0xFE, length, sequence, system id,
// component id, message id (1 byte), payload, checksum. These functions send unsigned MAVLink 2
// and read both versions, counting and dropping signed frames; signing and checking signatures is
// a layer below them (signing_link.hpp: signed frames are checked there and handed up unsigned).

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "swath/mavlink/payload.hpp"

namespace swath::mavlink {

inline constexpr std::uint8_t kStxV2 = 0xFD;
inline constexpr std::uint8_t kStxV1 = 0xFE;
inline constexpr std::uint8_t kIncompatSigned = 0x01;
inline constexpr std::size_t kMaxFrameBytes = 10 + 255 + 2 + 13;

/// Who sends a frame and its place in the sender's sequence.
struct FrameHeader {
  std::uint8_t seq = 0;
  std::uint8_t sysid = 0;
  std::uint8_t compid = 0;
};

/// One frame, payload as received (a MAVLink 2 payload may be truncated: unpack zero-fills it).
struct Frame {
  std::uint8_t version = 2;  ///< 1 or 2
  std::uint8_t incompat_flags = 0;
  std::uint8_t compat_flags = 0;
  FrameHeader header;
  std::uint32_t msgid = 0;
  std::uint8_t payload_length = 0;
  std::array<std::uint8_t, 255> payload{};
};

/// What swath knows of a message id: name, CRC_EXTRA and payload lengths (base, with extensions).
struct MessageInfo {
  std::uint32_t id = 0;
  std::string_view name;
  std::uint8_t crc_extra = 0;
  std::uint8_t base_length = 0;
  std::uint8_t max_length = 0;
};

/// The messages of messages.hpp, by id; nullptr for any other id.
const MessageInfo* find_message(std::uint32_t msgid);
/// All of them, in id order.
std::span<const MessageInfo> known_messages();

/// M as an unsigned MAVLink 2 frame.
template <class M>
Frame pack(const M& message, FrameHeader header) {
  Frame f;
  f.header = header;
  f.msgid = M::kId;
  f.payload_length = static_cast<std::uint8_t>(encode_payload(message, f.payload.data()));
  return f;
}

/// The frame's message as M, or nothing when it carries another message.
template <class M>
std::optional<M> unpack(const Frame& frame) {
  if (frame.msgid != M::kId) return std::nullopt;
  return decode_payload<M>(frame.payload.data(), frame.payload_length);
}

/// The frame's bytes with their checksum (`crc_extra` of its message id). MAVLink 1 frames need a
/// message id below 256 and carry the payload as given. Returns the number of bytes written to
/// `out`, which must hold kMaxFrameBytes.
std::size_t serialize(const Frame& frame, std::uint8_t crc_extra, std::uint8_t* out);
/// The same for a message swath knows (find_message); throws std::invalid_argument otherwise.
std::vector<std::uint8_t> serialize(const Frame& frame);

/// Counts of what a parser saw; every byte it was given is in exactly one of these.
struct ParserStats {
  std::uint64_t frames = 0;           ///< good frames of known messages, handed out
  std::uint64_t bytes_in_frames = 0;  ///< their bytes
  std::uint64_t unknown_id = 0;  ///< whole frames of messages swath does not know (not checked)
  std::uint64_t bytes_unknown = 0;
  std::uint64_t signed_dropped = 0;  ///< signed frames with a good checksum, dropped
  std::uint64_t bytes_signed = 0;
  std::uint64_t bad_crc = 0;        ///< start markers of known messages failing their checksum
  std::uint64_t bytes_skipped = 0;  ///< bytes outside any accepted frame (noise, bad frames)
};

/// Turns a byte stream (a serial line, UDP datagrams, a capture file) into frames. Bytes may come
/// in any split; a frame is handed out once all its bytes are in, and the frames handed out do not
/// depend on the split. Resynchronises after noise: a start marker whose frame fails its checksum
/// is skipped alone and the search goes on from the next byte. A frame of a message swath does not
/// know cannot be checked, so it is skipped whole only when no good frame of a known message
/// starts inside it (else its start marker was noise); a start marker in noise never swallows the
/// good frames its length would cover.
class FrameParser {
 public:
  /// Adds bytes to the stream.
  void feed(std::span<const std::uint8_t> bytes);
  /// The next complete good frame of a known message, or false when more bytes are needed.
  bool next(Frame& out);
  /// Says no more bytes will come (the end of a file): what waits for bytes is judged with what is
  /// there, so next() drains the stream and pending_bytes() ends at 0.
  void finish() { ended_ = true; }
  const ParserStats& stats() const { return stats_; }
  /// Bytes held while waiting for the rest of a frame (at most kMaxFrameBytes - 1 after next()
  /// returned false).
  std::size_t pending_bytes() const { return buffer_.size() - start_; }

 private:
  void compact();
  std::vector<std::uint8_t> buffer_;
  std::size_t start_ = 0;
  bool ended_ = false;
  ParserStats stats_;
};

/// The frame's message as text, "NAME field=value ...", MAVLink field names in wire order: numbers
/// as the shortest text that reads back to the same value (floats widened to double), char arrays
/// up to their first NUL, arrays as [a,b]. "#<id>" for a message swath does not know.
std::string describe(const Frame& frame);

}  // namespace swath::mavlink
