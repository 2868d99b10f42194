// A signing link (signing_link.hpp).
#include "swath/mavlink/signing_link.hpp"

#include <algorithm>
#include <array>

#include "swath/mavlink/crc.hpp"

namespace swath::mavlink {

SigningLink::SigningLink(std::unique_ptr<Link> link, const SigningKey& key, std::uint8_t link_id,
                         std::function<std::uint64_t()> clock)
    : link_(std::move(link)), key_(key), link_id_(link_id), clock_(std::move(clock)), check_(key) {}

std::uint64_t SigningLink::now() const {
  return clock_ ? clock_() : signing_timestamp_now();
}

// `bytes` is one MAVLink 2 frame (Endpoint sends one per call): parsed back and sent signed. What
// is not a MAVLink 2 frame of a known message goes nowhere: nothing leaves unsigned.
void SigningLink::send(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < 12 || bytes[0] != kStxV2) return;
  const std::uint32_t msgid =
      bytes[7] | (std::uint32_t{bytes[8]} << 8) | (std::uint32_t{bytes[9]} << 16);
  const MessageInfo* info = find_message(msgid);
  const std::size_t length = bytes[1];
  if (info == nullptr || bytes.size() != 10 + length + 2) return;
  Frame f;
  f.incompat_flags = 0;
  f.compat_flags = bytes[3];
  f.header = FrameHeader{bytes[4], bytes[5], bytes[6]};
  f.msgid = msgid;
  f.payload_length = static_cast<std::uint8_t>(length);
  std::copy_n(bytes.begin() + 10, length, f.payload.begin());
  last_sent_ = std::max(now(), last_sent_ + 1);  // strictly later than the last one
  std::array<std::uint8_t, kMaxFrameBytes> out{};
  const std::size_t n =
      serialize_signed(f, info->crc_extra, key_, link_id_, last_sent_, out.data());
  link_->send({out.data(), n});
  ++counts_.signed_sent;
}

namespace {
// Whether `packet` (one whole frame, header from its start marker) has the checksum of a message
// swath knows: a real frame rather than a start marker in noise.
bool checksum_good(std::span<const std::uint8_t> packet, bool v2, std::size_t length) {
  const std::uint32_t msgid =
      v2 ? packet[7] | (std::uint32_t{packet[8]} << 8) | (std::uint32_t{packet[9]} << 16)
         : packet[5];
  const MessageInfo* info = find_message(msgid);
  if (info == nullptr) return false;
  const std::size_t end = (v2 ? 10u : 6u) + length;
  const std::uint16_t crc = Crc16{}.add(packet.data() + 1, end - 1).add(info->crc_extra).value();
  return packet[end] == (crc & 0xFF) && packet[end + 1] == (crc >> 8);
}
}  // namespace

// Cuts what arrived into frames; hands on the accepted ones unsigned. A start marker whose frame
// has neither a good signature nor a good checksum is noise: skipped alone, the search goes on
// from the next byte.
std::size_t SigningLink::receive(std::vector<std::uint8_t>& out) {
  link_->receive(in_);
  const std::size_t before = out.size();
  std::size_t at = 0;
  const std::uint64_t t = now();
  while (at < in_.size()) {
    if (in_[at] != kStxV2 && in_[at] != kStxV1) {
      ++at;
      ++counts_.bytes_skipped;
      continue;
    }
    if (in_.size() - at < 3) break;  // the rest of its header later
    const bool v2 = in_[at] == kStxV2;
    const std::size_t length = in_[at + 1];
    const bool is_signed = v2 && (in_[at + 2] & kIncompatSigned) != 0;
    const std::size_t total = (v2 ? 10u : 6u) + length + 2u + (is_signed ? kSignatureBytes : 0u);
    if (in_.size() - at < total) break;  // the rest of the frame later
    const std::span<const std::uint8_t> packet(in_.data() + at, total);
    const SignatureCheck::Verdict v = check_.check(packet, t);
    if (v == SignatureCheck::Verdict::accepted) {
      pass_on(packet, out);
      ++counts_.accepted;
      at += total;
      continue;
    }
    const bool real = v == SignatureCheck::Verdict::replayed ||
                      v == SignatureCheck::Verdict::out_of_time ||
                      checksum_good(packet, v2, length);
    if (!real) {
      ++at;
      ++counts_.bytes_skipped;
      continue;
    }
    if (v == SignatureCheck::Verdict::not_signed)
      ++counts_.refused_unsigned;
    else if (v == SignatureCheck::Verdict::bad_signature)
      ++counts_.refused_signature;
    else
      ++counts_.refused_replay;
    at += total;
  }
  in_.erase(in_.begin(), in_.begin() + static_cast<long>(at));
  return out.size() - before;
}

// An accepted frame, unsigned again for the parser: the flag cleared, the checksum redone
// without it.
void SigningLink::pass_on(std::span<const std::uint8_t> packet, std::vector<std::uint8_t>& out) {
  const std::size_t plain = packet.size() - kSignatureBytes;
  const std::size_t start = out.size();
  out.insert(out.end(), packet.begin(), packet.begin() + static_cast<long>(plain));
  out[start + 2] &= static_cast<std::uint8_t>(~kIncompatSigned);
  const std::uint32_t msgid =
      packet[7] | (std::uint32_t{packet[8]} << 8) | (std::uint32_t{packet[9]} << 16);
  if (const MessageInfo* info = find_message(msgid)) {  // else the parser skips it anyway
    const std::uint16_t crc =
        Crc16{}.add(out.data() + start + 1, plain - 3).add(info->crc_extra).value();
    out[start + plain - 2] = static_cast<std::uint8_t>(crc & 0xFF);
    out[start + plain - 1] = static_cast<std::uint8_t>(crc >> 8);
  }
}

}  // namespace swath::mavlink
