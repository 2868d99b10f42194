#pragma once
// MAVLink 2 message signing (mavlink.io, "Message Signing"; docs/swath-fleet.md, "Signing"): a
// signed frame has incompat flag 0x01 and 13 more bytes after its checksum — the link id (1
// byte), a 48-bit timestamp in 10 µs units since 2015-01-01 00:00:00 UTC (6 bytes, little
// endian) and the first 6 bytes of SHA-256(secret key, 32 bytes || the frame from its 0xFD up to
// and including the checksum || link id || timestamp). A receiver accepts a signed frame when the
// signature matches and its timestamp is later than the last one accepted from the same (system,
// component, link id), and, for a stream not heard before, within a minute of its own clock.
// SHA-256 is swath's own (FIPS 180-4): OpenSSL is not among swath's dependencies.

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <tuple>

#include "swath/mavlink/frame.hpp"

namespace swath::mavlink {

using Sha256Digest = std::array<std::uint8_t, 32>;

/// SHA-256 (FIPS 180-4), fed in pieces.
class Sha256 {
 public:
  Sha256();
  Sha256& add(std::span<const std::uint8_t> bytes);
  /// The digest of everything added; the object is spent.
  Sha256Digest finish();

 private:
  void block(const std::uint8_t* b);
  std::array<std::uint32_t, 8> h_;
  std::array<std::uint8_t, 64> buffer_{};
  std::size_t buffered_ = 0;
  std::uint64_t length_bytes_ = 0;
};

Sha256Digest sha256(std::span<const std::uint8_t> bytes);

/// The secret both ends share.
struct SigningKey {
  std::array<std::uint8_t, 32> secret{};
};

/// A key file's contents: exactly 32 bytes (raw), or 64 hexadecimal digits with optional white
/// space around them (what `openssl rand -hex 32` prints). Anything else throws base::InputError
/// naming `source`.
SigningKey parse_signing_key(std::string_view contents, const std::string& source);

/// 2015-01-01 00:00:00 UTC in Unix seconds: the signing timestamp's epoch.
inline constexpr std::uint64_t kSigningEpochUnixS = 1420070400;
/// The wall clock as a signing timestamp (10 µs units since kSigningEpochUnixS).
std::uint64_t signing_timestamp_now();

inline constexpr std::size_t kSignatureBytes = 13;

/// The frame's bytes, signed: incompat flag 0x01 set (the checksum covers it), then link id,
/// timestamp (the low 48 bits) and signature. `out` must hold kMaxFrameBytes. Returns the bytes
/// written. MAVLink 2 only (std::invalid_argument for a version 1 frame).
std::size_t serialize_signed(const Frame& frame, std::uint8_t crc_extra, const SigningKey& key,
                             std::uint8_t link_id, std::uint64_t timestamp, std::uint8_t* out);

/// Judges the signed frames that arrive on one link.
class SignatureCheck {
 public:
  enum class Verdict { accepted, not_signed, bad_signature, replayed, out_of_time };
  explicit SignatureCheck(const SigningKey& key) : key_(key) {}
  /// `packet`: one whole MAVLink 2 frame as received, signature included. `now`: the receiver's
  /// clock as a signing timestamp. Accepting a frame records its timestamp for its stream.
  Verdict check(std::span<const std::uint8_t> packet, std::uint64_t now);

 private:
  SigningKey key_;
  std::map<std::tuple<std::uint8_t, std::uint8_t, std::uint8_t>, std::uint64_t> last_;
};

}  // namespace swath::mavlink
