#pragma once
// A Link that signs what goes out and lets in only frames signed with its key (signing.hpp;
// docs/swath-fleet.md, "Signing"): `swath-fleet run --signing-key FILE` puts one over each
// vehicle's link, and FakeCopter over one speaks as a vehicle configured with the same key.
// Out: each send() is one frame (what Endpoint sends), re-sent signed — the incompat flag set,
// the checksum redone, link id, timestamp (the wall clock in 10 µs units since 2015, always
// later than the last one sent) and signature appended. In: the bytes are cut into frames;
// a frame signed with the key, later than the last one accepted from its (system, component,
// link id), goes on without its signature (so the parser above reads it as any frame); unsigned
// frames, frames with another signature, replays and noise are dropped and counted.

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "swath/mavlink/link.hpp"
#include "swath/mavlink/signing.hpp"

namespace swath::mavlink {

struct SigningCounts {
  std::uint64_t signed_sent = 0;
  std::uint64_t accepted = 0;
  std::uint64_t refused_unsigned = 0;  ///< unsigned frames (MAVLink 1 included)
  std::uint64_t refused_signature = 0;
  std::uint64_t refused_replay = 0;  ///< not later than the last accepted, or a minute old
  std::uint64_t bytes_skipped = 0;   ///< noise between frames
};

class SigningLink final : public Link {
 public:
  /// `clock`: the signing timestamp to use now (tests give their own); default the wall clock.
  SigningLink(std::unique_ptr<Link> link, const SigningKey& key, std::uint8_t link_id,
              std::function<std::uint64_t()> clock = {});
  void send(std::span<const std::uint8_t> bytes) override;
  std::size_t receive(std::vector<std::uint8_t>& out) override;
  const SigningCounts& counts() const { return counts_; }

 private:
  std::uint64_t now() const;
  static void pass_on(std::span<const std::uint8_t> packet, std::vector<std::uint8_t>& out);
  std::unique_ptr<Link> link_;
  SigningKey key_;
  std::uint8_t link_id_;
  std::function<std::uint64_t()> clock_;
  SignatureCheck check_;
  std::uint64_t last_sent_ = 0;
  std::vector<std::uint8_t> in_;  // bytes received, not yet a whole frame
  SigningCounts counts_;
};

}  // namespace swath::mavlink
