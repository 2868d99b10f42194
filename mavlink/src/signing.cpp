// MAVLink 2 signing and SHA-256 (signing.hpp).
#include "swath/mavlink/signing.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstring>
#include <stdexcept>

#include "swath/base/input_error.hpp"
#include "swath/mavlink/crc.hpp"

namespace swath::mavlink {

namespace {

constexpr std::array<std::uint32_t, 64> kRound{
    0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5,
    0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174,
    0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da,
    0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967,
    0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85,
    0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070,
    0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
    0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2};

constexpr std::uint32_t rotr(std::uint32_t x, int n) {
  return (x >> n) | (x << (32 - n));
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// The signature: the first 6 bytes of SHA-256(key || frame up to its checksum || link id ||
// timestamp), `signed_part` being the frame with those 7 bytes after it.
std::array<std::uint8_t, 6> signature_of(const SigningKey& key,
                                         std::span<const std::uint8_t> signed_part) {
  const Sha256Digest d = Sha256{}.add(key.secret).add(signed_part).finish();
  std::array<std::uint8_t, 6> s{};
  std::copy_n(d.begin(), 6, s.begin());
  return s;
}

}  // namespace

Sha256::Sha256()
    : h_{0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a,
         0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19} {}

void Sha256::block(const std::uint8_t* b) {
  std::array<std::uint32_t, 64> w{};
  for (int i = 0; i < 16; ++i)
    w[i] = (std::uint32_t{b[4 * i]} << 24) | (std::uint32_t{b[4 * i + 1]} << 16) |
           (std::uint32_t{b[4 * i + 2]} << 8) | std::uint32_t{b[4 * i + 3]};
  for (int i = 16; i < 64; ++i) {
    const std::uint32_t s0 = rotr(w[i - 15], 7) ^ rotr(w[i - 15], 18) ^ (w[i - 15] >> 3);
    const std::uint32_t s1 = rotr(w[i - 2], 17) ^ rotr(w[i - 2], 19) ^ (w[i - 2] >> 10);
    w[i] = w[i - 16] + s0 + w[i - 7] + s1;
  }
  auto [a, b_, c, d, e, f, g, h] = h_;
  for (int i = 0; i < 64; ++i) {
    const std::uint32_t t1 =
        h + (rotr(e, 6) ^ rotr(e, 11) ^ rotr(e, 25)) + ((e & f) ^ (~e & g)) + kRound[i] + w[i];
    const std::uint32_t t2 =
        (rotr(a, 2) ^ rotr(a, 13) ^ rotr(a, 22)) + ((a & b_) ^ (a & c) ^ (b_ & c));
    h = g;
    g = f;
    f = e;
    e = d + t1;
    d = c;
    c = b_;
    b_ = a;
    a = t1 + t2;
  }
  const std::array<std::uint32_t, 8> add{a, b_, c, d, e, f, g, h};
  for (int i = 0; i < 8; ++i) h_[i] += add[i];
}

Sha256& Sha256::add(std::span<const std::uint8_t> bytes) {
  length_bytes_ += bytes.size();
  for (const std::uint8_t byte : bytes) {
    buffer_[buffered_++] = byte;
    if (buffered_ == 64) {
      block(buffer_.data());
      buffered_ = 0;
    }
  }
  return *this;
}

Sha256Digest Sha256::finish() {
  const std::uint64_t bits = length_bytes_ * 8;
  const std::uint8_t one = 0x80, zero = 0;
  add({&one, 1});
  while (buffered_ != 56) add({&zero, 1});
  std::array<std::uint8_t, 8> length{};
  for (int i = 0; i < 8; ++i) length[i] = static_cast<std::uint8_t>(bits >> (56 - 8 * i));
  add(length);
  Sha256Digest out{};
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 4; ++k) out[4 * i + k] = static_cast<std::uint8_t>(h_[i] >> (24 - 8 * k));
  return out;
}

Sha256Digest sha256(std::span<const std::uint8_t> bytes) {
  return Sha256{}.add(bytes).finish();
}

SigningKey parse_signing_key(std::string_view contents, const std::string& source) {
  SigningKey key;
  if (contents.size() == key.secret.size()) {
    std::memcpy(key.secret.data(), contents.data(), key.secret.size());
    return key;
  }
  std::string_view hex = contents;
  while (!hex.empty() && std::isspace(static_cast<unsigned char>(hex.front())))
    hex.remove_prefix(1);
  while (!hex.empty() && std::isspace(static_cast<unsigned char>(hex.back()))) hex.remove_suffix(1);
  bool all_hex = hex.size() == 64;
  for (std::size_t i = 0; all_hex && i < 32; ++i) {
    const int hi = hex_value(hex[2 * i]), lo = hex_value(hex[2 * i + 1]);
    all_hex = hi >= 0 && lo >= 0;
    if (all_hex) key.secret[i] = static_cast<std::uint8_t>(hi * 16 + lo);
  }
  if (!all_hex)
    throw base::InputError(source + ": a signing key is 32 bytes, or 64 hexadecimal digits (" +
                           std::to_string(contents.size()) + " bytes here)");
  return key;
}

std::uint64_t signing_timestamp_now() {
  const auto since_unix = std::chrono::system_clock::now().time_since_epoch();
  const auto us = std::chrono::duration_cast<std::chrono::microseconds>(since_unix).count();
  return (static_cast<std::uint64_t>(us) - kSigningEpochUnixS * 1000000) / 10;
}

std::size_t serialize_signed(const Frame& frame, std::uint8_t crc_extra, const SigningKey& key,
                             std::uint8_t link_id, std::uint64_t timestamp, std::uint8_t* out) {
  if (frame.version != 2) throw std::invalid_argument("only MAVLink 2 frames are signed");
  std::size_t n = serialize(frame, crc_extra, out);
  out[2] |= kIncompatSigned;  // the flag is part of what the checksum covers
  const std::uint16_t crc = Crc16{}.add(out + 1, n - 3).add(crc_extra).value();
  out[n - 2] = static_cast<std::uint8_t>(crc & 0xFF);
  out[n - 1] = static_cast<std::uint8_t>(crc >> 8);
  out[n++] = link_id;
  for (int i = 0; i < 6; ++i) out[n++] = static_cast<std::uint8_t>(timestamp >> (8 * i));
  const auto s = signature_of(key, {out, n});
  std::copy(s.begin(), s.end(), out + n);
  return n + 6;
}

SignatureCheck::Verdict SignatureCheck::check(std::span<const std::uint8_t> packet,
                                              std::uint64_t now) {
  if (packet.size() < 10 + kSignatureBytes || packet[0] != kStxV2 ||
      (packet[2] & kIncompatSigned) == 0)
    return Verdict::not_signed;
  const std::size_t signed_length = packet.size() - 6;
  const auto expected = signature_of(key_, packet.first(signed_length));
  if (!std::equal(expected.begin(), expected.end(), packet.begin() + signed_length))
    return Verdict::bad_signature;
  const std::uint8_t link_id = packet[packet.size() - kSignatureBytes];
  std::uint64_t timestamp = 0;
  for (int i = 0; i < 6; ++i) timestamp |= std::uint64_t{packet[packet.size() - 12 + i]} << (8 * i);
  const auto stream = std::make_tuple(packet[5], packet[6], link_id);
  const auto last = last_.find(stream);
  if (last != last_.end() && timestamp <= last->second) return Verdict::replayed;
  constexpr std::uint64_t kMinute = 6000000;             // 10 µs units
  if (last == last_.end() && timestamp + kMinute < now)  // a new stream a minute old
    return Verdict::out_of_time;
  last_[stream] = timestamp;
  return Verdict::accepted;
}

}  // namespace swath::mavlink
