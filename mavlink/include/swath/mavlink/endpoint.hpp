#pragma once
// One MAVLink node on a link: its own system and component ids, its sequence counter, and a parser
// for what arrives.

#include <cstdint>
#include <vector>

#include "swath/mavlink/frame.hpp"
#include "swath/mavlink/link.hpp"

namespace swath::mavlink {

class Endpoint {
 public:
  Endpoint(Link& link, std::uint8_t sysid, std::uint8_t compid)
      : link_(link), sysid_(sysid), compid_(compid) {}

  /// Sends M as the next frame of this node's sequence.
  template <class M>
  void send(const M& message) {
    const Frame frame = pack(message, FrameHeader{seq_++, sysid_, compid_});
    std::array<std::uint8_t, kMaxFrameBytes> bytes;
    const std::size_t n = serialize(frame, crc_extra<M>(), bytes.data());
    link_.send({bytes.data(), n});
    ++frames_sent_;
  }

  /// The good frames that arrived since the last call, in order.
  std::vector<Frame> receive() {
    scratch_.clear();
    link_.receive(scratch_);
    parser_.feed(scratch_);
    std::vector<Frame> frames;
    for (Frame f; parser_.next(f);) frames.push_back(f);
    return frames;
  }

  std::uint8_t sysid() const { return sysid_; }
  std::uint8_t compid() const { return compid_; }
  std::uint64_t frames_sent() const { return frames_sent_; }
  const ParserStats& received() const { return parser_.stats(); }

 private:
  Link& link_;
  std::uint8_t sysid_, compid_;
  std::uint8_t seq_ = 0;
  std::uint64_t frames_sent_ = 0;
  FrameParser parser_;
  std::vector<std::uint8_t> scratch_;
};

}  // namespace swath::mavlink
