#include "swath/mavlink/frame.hpp"

#include <algorithm>
#include <charconv>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "swath/mavlink/crc.hpp"
#include "swath/mavlink/messages.hpp"

namespace swath::mavlink {
namespace {

constexpr std::size_t kMessageCount = [] {
  std::size_t n = 0;
  for_each_message([&n](auto) { ++n; });
  return n;
}();

constexpr std::array<MessageInfo, kMessageCount> kRegistry = [] {
  std::array<MessageInfo, kMessageCount> table{};
  std::size_t i = 0;
  for_each_message([&](auto m) {
    using M = decltype(m);
    table[i++] = MessageInfo{M::kId, M::kName, crc_extra<M>(),
                             static_cast<std::uint8_t>(base_payload_length<M>()),
                             static_cast<std::uint8_t>(max_payload_length<M>())};
  });
  return table;
}();

static_assert(std::is_sorted(kRegistry.begin(), kRegistry.end(),
                             [](const MessageInfo& a, const MessageInfo& b) {
                               return a.id < b.id;
                             }),
              "for_each_message lists messages in id order");
static_assert(max_payload_length<CameraImageCaptured>() == 255);
static_assert(Crc16{}.add("123456789").value() == 0x6F91, "CRC-16/MCRF4XX check value");

std::size_t header_bytes(std::uint8_t stx) {
  return stx == kStxV2 ? 10 : 6;
}

// Text of one value for describe(): integers exact, floating point shortest round trip.
template <class E>
void append_number(std::string& out, E value) {
  char buf[64];
  std::to_chars_result r;
  if constexpr (std::is_floating_point_v<E>) {
    r = std::to_chars(buf, buf + sizeof buf, static_cast<double>(value));
  } else if constexpr (sizeof(E) == 1) {
    r = std::to_chars(buf, buf + sizeof buf, static_cast<int>(value));
  } else {
    r = std::to_chars(buf, buf + sizeof buf, value);
  }
  out.append(buf, r.ptr);
}

struct Describer {
  std::string& out;
  template <class T>
  void field(const T& value, std::string_view name) {
    using Shape = detail::FieldShape<T>;
    using E = typename Shape::Element;
    out.append(" ").append(name).append("=");
    if constexpr (Shape::count == 0) {
      append_number<E>(out, value);
    } else if constexpr (std::is_same_v<E, char>) {
      const auto end = std::find(value.begin(), value.end(), '\0');
      out.append(value.begin(), end);
    } else {
      out.append("[");
      for (std::size_t i = 0; i < value.size(); ++i) {
        if (i > 0) out.append(",");
        append_number<E>(out, value[i]);
      }
      out.append("]");
    }
  }
  template <class T>
  void extension(const T& value, std::string_view name) {
    field(value, name);
  }
};

}  // namespace

const MessageInfo* find_message(std::uint32_t msgid) {
  const auto it =
      std::lower_bound(kRegistry.begin(), kRegistry.end(), msgid,
                       [](const MessageInfo& m, std::uint32_t id) { return m.id < id; });
  return it != kRegistry.end() && it->id == msgid ? &*it : nullptr;
}

std::span<const MessageInfo> known_messages() {
  return kRegistry;
}

std::size_t serialize(const Frame& frame, std::uint8_t crc_extra, std::uint8_t* out) {
  std::size_t n = 0;
  if (frame.version == 1) {
    if (frame.msgid > 255) throw std::invalid_argument("MAVLink 1 carries message ids up to 255");
    out[n++] = kStxV1;
    out[n++] = frame.payload_length;
    out[n++] = frame.header.seq;
    out[n++] = frame.header.sysid;
    out[n++] = frame.header.compid;
    out[n++] = static_cast<std::uint8_t>(frame.msgid);
  } else {
    out[n++] = kStxV2;
    out[n++] = frame.payload_length;
    out[n++] = static_cast<std::uint8_t>(frame.incompat_flags & ~kIncompatSigned);
    out[n++] = frame.compat_flags;
    out[n++] = frame.header.seq;
    out[n++] = frame.header.sysid;
    out[n++] = frame.header.compid;
    out[n++] = static_cast<std::uint8_t>(frame.msgid);
    out[n++] = static_cast<std::uint8_t>(frame.msgid >> 8);
    out[n++] = static_cast<std::uint8_t>(frame.msgid >> 16);
  }
  std::copy_n(frame.payload.begin(), frame.payload_length, out + n);
  n += frame.payload_length;
  const std::uint16_t crc = Crc16{}.add(out + 1, n - 1).add(crc_extra).value();
  out[n++] = static_cast<std::uint8_t>(crc & 0xFF);
  out[n++] = static_cast<std::uint8_t>(crc >> 8);
  return n;
}

std::vector<std::uint8_t> serialize(const Frame& frame) {
  const MessageInfo* info = find_message(frame.msgid);
  if (info == nullptr)
    throw std::invalid_argument("no CRC_EXTRA for MAVLink message id " +
                                std::to_string(frame.msgid));
  std::vector<std::uint8_t> bytes(kMaxFrameBytes);
  bytes.resize(serialize(frame, info->crc_extra, bytes.data()));
  return bytes;
}

void FrameParser::feed(std::span<const std::uint8_t> bytes) {
  compact();
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
}

void FrameParser::compact() {
  if (start_ == 0) return;
  buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(start_));
  start_ = 0;
}

namespace {

// A frame starting at f (a start marker) with `available` bytes from there on.
struct Candidate {
  enum Status { kIncomplete, kNotAFrame, kKnown, kUnknownId } status = kNotAFrame;
  bool header_known = false;  // head, total, msgid and info filled in
  std::size_t head = 0, total = 0;
  std::uint32_t msgid = 0;
  std::uint8_t incompat = 0;
  const MessageInfo* info = nullptr;
};

Candidate examine(const std::uint8_t* f, std::size_t available) {
  Candidate c;
  const bool v2 = f[0] == kStxV2;
  c.head = header_bytes(f[0]);
  if (available < c.head) return {Candidate::kIncomplete};
  const std::uint8_t length = f[1];
  c.incompat = v2 ? f[2] : 0;
  if ((c.incompat & ~kIncompatSigned) != 0) return {Candidate::kNotAFrame};  // flags unknown to us
  c.header_known = true;
  c.total = c.head + length + 2 + ((c.incompat & kIncompatSigned) != 0 ? 13 : 0);
  c.msgid = v2 ? std::uint32_t(f[7]) | std::uint32_t(f[8]) << 8 | std::uint32_t(f[9]) << 16 : f[5];
  c.info = find_message(c.msgid);
  if (available < c.total) {
    c.status = Candidate::kIncomplete;
  } else if (c.info == nullptr) {
    c.status = Candidate::kUnknownId;
  } else {
    const std::uint16_t crc =
        Crc16{}.add(f + 1, c.head - 1 + length).add(c.info->crc_extra).value();
    const std::uint16_t sent =
        static_cast<std::uint16_t>(f[c.head + length] | f[c.head + length + 1] << 8);
    c.status = crc == sent ? Candidate::kKnown : Candidate::kNotAFrame;
  }
  return c;
}

// Whether a good frame of a known message starts in data[from, to) (complete and checked), and
// whether a start marker there still waits for bytes.
struct InnerScan {
  bool good_frame = false;
  bool waiting = false;
};
InnerScan scan_inside(const std::uint8_t* data, std::size_t size, std::size_t from,
                      std::size_t to) {
  InnerScan r;
  for (std::size_t p = from; p < to; ++p) {
    if (data[p] != kStxV2 && data[p] != kStxV1) continue;
    const Candidate inner = examine(data + p, size - p);
    if (inner.status == Candidate::kKnown) return {true, r.waiting};
    if (inner.status == Candidate::kIncomplete) r.waiting = true;
  }
  return r;
}

}  // namespace

// Every decision below depends only on bytes that are in, and is taken only when the bytes that
// could change it are in too: so the frames handed out do not depend on how the stream is split.
bool FrameParser::next(Frame& out) {
  const std::uint8_t* data = buffer_.data();
  const std::size_t size = buffer_.size();
  const auto skip_one = [this] {
    ++stats_.bytes_skipped;
    ++start_;
  };
  while (start_ < size) {
    const std::uint8_t stx = data[start_];
    if (stx != kStxV2 && stx != kStxV1) {
      skip_one();
      continue;
    }
    const std::uint8_t* f = data + start_;
    const Candidate c = examine(f, size - start_);
    if (c.status == Candidate::kNotAFrame) {  // noise, or a frame hit by it: resynchronise
      if (c.header_known) ++stats_.bad_crc;
      skip_one();
      continue;
    }
    if (c.status == Candidate::kIncomplete && ended_) {  // never completed: noise
      skip_one();
      continue;
    }
    if (c.status == Candidate::kIncomplete && (!c.header_known || c.info != nullptr))
      return false;  // a known message: its checksum will tell
    if (c.status != Candidate::kKnown) {
      // A message whose checksum cannot be checked: its length is not to be trusted. A good frame
      // of a known message starting inside it shows it is noise (a real frame does not hold
      // another); otherwise it is skipped whole once every start marker inside could be judged.
      const InnerScan inner = scan_inside(data, size, start_ + 1, std::min(size, start_ + c.total));
      if (inner.good_frame) {
        skip_one();
        continue;
      }
      if (c.status == Candidate::kIncomplete || (inner.waiting && !ended_)) return false;
      ++stats_.unknown_id;
      stats_.bytes_unknown += c.total;
      start_ += c.total;
      continue;
    }
    start_ += c.total;
    if ((c.incompat & kIncompatSigned) != 0) {
      ++stats_.signed_dropped;
      stats_.bytes_signed += c.total;
      continue;
    }
    const bool v2 = stx == kStxV2;
    const std::uint8_t length = f[1];
    out.version = v2 ? 2 : 1;
    out.incompat_flags = c.incompat;
    out.compat_flags = v2 ? f[3] : 0;
    out.header = FrameHeader{f[v2 ? 4u : 2u], f[v2 ? 5u : 3u], f[v2 ? 6u : 4u]};
    out.msgid = c.msgid;
    out.payload_length = length;
    std::copy_n(f + c.head, length, out.payload.begin());
    std::fill(out.payload.begin() + length, out.payload.end(), std::uint8_t{0});
    ++stats_.frames;
    stats_.bytes_in_frames += c.total;
    return true;
  }
  return false;
}

std::string describe(const Frame& frame) {
  std::string out;
  bool found = false;
  for_each_message([&](auto m) {
    using M = decltype(m);
    if (found || frame.msgid != M::kId) return;
    found = true;
    out.append(M::kName);
    M message = decode_payload<M>(frame.payload.data(), frame.payload_length);
    Describer d{out};
    message.fields(d);
  });
  if (!found) out = "#" + std::to_string(frame.msgid);
  return out;
}

}  // namespace swath::mavlink
