// swath's MAVLink codec on its own: the checksum against a bit-by-bit reference, every message
// through pack -> bytes -> parser -> unpack with random field values, MAVLink 2's truncation and
// MAVLink 1 frames, and the parser on split, noisy, corrupted, signed and unknown input with every
// byte accounted for. node-mavlink's view of the same bytes: codec_oracle_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include "mavlink_test_support.hpp"
#include "swath/mavlink/frame.hpp"
#include "swath/mavlink/messages.hpp"

namespace swath::mavlink {
namespace {

// CRC-16/MCRF4XX one bit at a time (reflected polynomial 0x8408): independent of Crc16's folding.
std::uint16_t crc_bitwise(const std::vector<std::uint8_t>& bytes) {
  std::uint16_t crc = 0xFFFF;
  for (std::uint8_t b : bytes) {
    crc ^= b;
    for (int i = 0; i < 8; ++i)
      crc = (crc & 1) ? static_cast<std::uint16_t>((crc >> 1) ^ 0x8408)
                      : static_cast<std::uint16_t>(crc >> 1);
  }
  return crc;
}

// The mission protocol's and PARAM_SET's CRC_EXTRA seeds and lengths as MAVLink's own generator
// wrote them into ArduPilot's headers (mavlink_msg_*.h: *_CRC, *_MIN_LEN, *_LEN), copied by hand:
// a second derivation beside the node-mavlink oracle. MISSION_COUNT and MISSION_ACK carry the
// later extension opaque_id (uint32) of today's common.xml, as node-mavlink decodes them: 4 bytes
// more than the headers ArduPilot 4.7 was generated with (MAVLink 2 trims trailing zero bytes, so
// with opaque_id 0 the frames on the wire are the same for both).
TEST(Registry, MissionAndParamSetSeedsEqualMavgensHeaders) {
  struct Row {
    std::uint32_t id;
    int crc, min_len, len;
  };
  for (const Row& r :
       {Row{23, 168, 23, 23}, Row{40, 230, 4, 5}, Row{43, 132, 2, 3}, Row{44, 221, 4, 5 + 4},
        Row{47, 153, 3, 4 + 4}, Row{51, 196, 4, 5}, Row{73, 38, 37, 38}}) {
    const MessageInfo* m = find_message(r.id);
    ASSERT_NE(m, nullptr) << r.id;
    EXPECT_EQ(m->crc_extra, r.crc) << m->name;
    EXPECT_EQ(m->base_length, r.min_len) << m->name;
    EXPECT_EQ(m->max_length, r.len) << m->name;
  }
}

TEST(Crc16, EqualsTheBitwiseDefinitionOnRandomBytes) {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<std::uint8_t> bytes(rng() % 300);
    for (auto& b : bytes) b = static_cast<std::uint8_t>(rng());
    EXPECT_EQ(Crc16{}.add(bytes.data(), bytes.size()).value(), crc_bitwise(bytes));
  }
  const std::string check = "123456789";
  EXPECT_EQ(crc_bitwise({check.begin(), check.end()}), 0x6F91);  // the catalogue's check value
}

TEST(Registry, KnowsEachMessageOnceWithItsLengths) {
  const auto messages = known_messages();
  ASSERT_EQ(messages.size(), 30u);
  for (const MessageInfo& m : messages) {
    ASSERT_EQ(find_message(m.id), &m) << m.name;
    EXPECT_LE(m.base_length, m.max_length) << m.name;
    EXPECT_GT(m.base_length, 0) << m.name;
  }
  EXPECT_EQ(find_message(9999), nullptr);
  EXPECT_EQ(find_message(3), nullptr);
  // MAVLink 1 payloads are the base fields only: HEARTBEAT 9 bytes, GLOBAL_POSITION_INT 28.
  EXPECT_EQ(find_message(Heartbeat::kId)->base_length, 9);
  EXPECT_EQ(find_message(GlobalPositionInt::kId)->max_length, 28);
}

TEST(Codec, EveryMessageRoundTripsThroughBytesAndTheParser) {
  std::mt19937_64 rng(5);
  for_each_message([&](auto sample) {
    using M = decltype(sample);
    for (int trial = 0; trial < 100; ++trial) {
      const M sent = test::random_message<M>(rng, 0.3);
      const FrameHeader header{static_cast<std::uint8_t>(trial), 7, 190};
      const Frame frame = pack(sent, header);
      const std::vector<std::uint8_t> bytes = serialize(frame);
      FrameParser parser;
      parser.feed(bytes);
      Frame got;
      ASSERT_TRUE(parser.next(got)) << M::kName;
      EXPECT_FALSE(parser.next(got));
      EXPECT_EQ(got.header.seq, header.seq);
      EXPECT_EQ(got.header.sysid, 7);
      EXPECT_EQ(got.header.compid, 190);
      EXPECT_EQ(got.msgid, M::kId);
      const auto back = unpack<M>(got);
      ASSERT_TRUE(back.has_value());
      EXPECT_EQ(test::full_payload(*back), test::full_payload(sent)) << M::kName;  // bit for bit
      EXPECT_EQ(parser.stats().bytes_in_frames, bytes.size());
    }
  });
}

TEST(Codec, TrailingZerosAreNotSentAndReadBackAsZeros) {
  GlobalPositionInt g;
  g.time_boot_ms = 1000;
  g.lat_degE7 = 473977420;  // the rest zero: the payload ends after lat
  const Frame f = pack(g, {});
  EXPECT_EQ(f.payload_length, 8);
  EXPECT_EQ(unpack<GlobalPositionInt>(f)->lat_degE7, 473977420);
  EXPECT_EQ(unpack<GlobalPositionInt>(f)->hdg_cdeg, 0);
  const Frame empty = pack(Heartbeat{.mavlink_version = 0}, {});
  EXPECT_EQ(empty.payload_length, 1);  // never empty
  EXPECT_EQ(serialize(empty).size(), 10u + 1 + 2);
  EXPECT_FALSE(unpack<SysStatus>(f).has_value());
}

TEST(Codec, MavlinkOneFramesCarryTheBaseFieldsAndParse) {
  SysStatus s;
  s.voltage_battery_mV = 12600;
  s.battery_remaining_percent = 87;
  s.onboard_control_sensors_health_extended = 5;  // an extension: not in MAVLink 1
  Frame f = pack(s, {3, 1, 1});
  f.version = 1;
  f.payload_length = find_message(SysStatus::kId)->base_length;
  const auto bytes = serialize(f);
  ASSERT_EQ(bytes[0], kStxV1);
  EXPECT_EQ(bytes.size(), 6u + 31 + 2);
  FrameParser parser;
  parser.feed(bytes);
  Frame got;
  ASSERT_TRUE(parser.next(got));
  EXPECT_EQ(got.version, 1);
  const SysStatus back = *unpack<SysStatus>(got);
  EXPECT_EQ(back.voltage_battery_mV, 12600);
  EXPECT_EQ(back.battery_remaining_percent, 87);
  EXPECT_EQ(back.onboard_control_sensors_health_extended, 0u);
  Frame big = pack(CameraImageCaptured{}, {});
  big.msgid = 263;
  big.version = 1;
  EXPECT_THROW(serialize(big), std::invalid_argument);
}

// A stream of random frames with noise between them, fed in random pieces: the same frames come
// out whatever the pieces, and every byte is in one count.
TEST(Parser, AnySplitAndNoiseGiveTheSameFramesAndEveryByteIsCounted) {
  std::mt19937_64 rng(19);
  for (int trial = 0; trial < 30; ++trial) {
    std::vector<std::uint8_t> stream;
    std::vector<std::vector<std::uint8_t>> sent;
    for (int i = 0; i < 60; ++i) {
      if (rng() % 3 == 0) {  // noise, sometimes holding a start marker
        const std::size_t n = rng() % 20;
        for (std::size_t k = 0; k < n; ++k)
          stream.push_back(rng() % 8 == 0 ? kStxV2 : static_cast<std::uint8_t>(rng()));
      }
      const Frame f = test::random_frame(rng, static_cast<std::uint8_t>(i));
      sent.push_back(serialize(f));
      stream.insert(stream.end(), sent.back().begin(), sent.back().end());
    }
    FrameParser parser;
    std::vector<std::vector<std::uint8_t>> got;
    std::size_t at = 0;
    while (at < stream.size()) {
      const std::size_t n = std::min<std::size_t>(1 + rng() % 90, stream.size() - at);
      parser.feed({stream.data() + at, n});
      at += n;
      Frame f;
      while (parser.next(f)) got.push_back(serialize(f));
    }
    parser.finish();  // noise near the end may claim bytes that never come
    for (Frame f; parser.next(f);) got.push_back(serialize(f));
    // A start marker in noise is judged by its checksum (known message: one byte skipped when it
    // fails) or, for an unknown message, by the good frames inside the length it claims; a
    // false frame would need a matching checksum (1 in 65,536). So every frame comes out, in order.
    ASSERT_EQ(got.size(), sent.size()) << "trial " << trial;
    EXPECT_EQ(got, sent);
    const ParserStats& s = parser.stats();
    EXPECT_EQ(s.bytes_in_frames + s.bytes_skipped + s.bytes_unknown + s.bytes_signed,
              stream.size());
    EXPECT_EQ(parser.pending_bytes(), 0u);
  }
}

TEST(Parser, CorruptedFrameIsLostAloneAndTheNextIsFound) {
  std::mt19937_64 rng(3);
  std::vector<std::uint8_t> stream;
  std::vector<std::vector<std::uint8_t>> frames;
  for (int i = 0; i < 3; ++i) {
    frames.push_back(serialize(test::random_frame(rng, static_cast<std::uint8_t>(i))));
    stream.insert(stream.end(), frames.back().begin(), frames.back().end());
  }
  stream[frames[0].size() + 11] ^= 0x40;  // a payload byte of the second frame
  FrameParser parser;
  parser.feed(stream);
  std::vector<std::vector<std::uint8_t>> got;
  Frame f;
  while (parser.next(f)) got.push_back(serialize(f));
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0], frames[0]);
  EXPECT_EQ(got[1], frames[2]);
  EXPECT_EQ(parser.stats().bad_crc, 1u);
  EXPECT_EQ(parser.stats().bytes_skipped, frames[1].size());
}

TEST(Parser, SignedFramesAreCountedAndDroppedUnknownIdsSkippedWhole) {
  Frame hb = pack(Heartbeat{.type = 2, .autopilot = 3}, {1, 1, 1});
  hb.incompat_flags = kIncompatSigned;  // serialize clears the flag: set it by hand below
  std::vector<std::uint8_t> signed_frame = serialize(hb);
  signed_frame[2] = kIncompatSigned;
  // The checksum covers the flags: recompute it, then append a 13-byte signature.
  const std::size_t body = signed_frame.size() - 2;
  const std::uint16_t crc = Crc16{}
                                .add(signed_frame.data() + 1, body - 1)
                                .add(find_message(Heartbeat::kId)->crc_extra)
                                .value();
  signed_frame[body] = static_cast<std::uint8_t>(crc & 0xFF);
  signed_frame[body + 1] = static_cast<std::uint8_t>(crc >> 8);
  signed_frame.insert(signed_frame.end(), 13, 0xAB);

  Frame unknown = pack(Heartbeat{}, {2, 1, 1});
  unknown.msgid = 4;  // PING: not one of swath's messages
  std::vector<std::uint8_t> unknown_bytes(kMaxFrameBytes);
  unknown_bytes.resize(serialize(unknown, 237, unknown_bytes.data()));

  const auto plain = serialize(pack(Heartbeat{.type = 6}, {3, 1, 1}));
  std::vector<std::uint8_t> stream = signed_frame;
  stream.insert(stream.end(), unknown_bytes.begin(), unknown_bytes.end());
  stream.insert(stream.end(), plain.begin(), plain.end());
  FrameParser parser;
  parser.feed(stream);
  Frame f;
  ASSERT_TRUE(parser.next(f));
  EXPECT_EQ(f.header.seq, 3);
  EXPECT_EQ(unpack<Heartbeat>(f)->type, 6);
  EXPECT_FALSE(parser.next(f));
  EXPECT_EQ(parser.stats().signed_dropped, 1u);
  EXPECT_EQ(parser.stats().bytes_signed, signed_frame.size());
  EXPECT_EQ(parser.stats().unknown_id, 1u);
  EXPECT_EQ(parser.stats().bytes_unknown, unknown_bytes.size());
  EXPECT_EQ(parser.stats().bytes_skipped, 0u);
}

TEST(Parser, AFrameWaitsForItsLastByte) {
  const auto bytes = serialize(pack(GlobalPositionInt{.lat_degE7 = 1, .hdg_cdeg = 9000}, {}));
  FrameParser parser;
  Frame f;
  for (std::size_t i = 0; i + 1 < bytes.size(); ++i) {
    parser.feed({bytes.data() + i, 1});
    EXPECT_FALSE(parser.next(f)) << i;
  }
  EXPECT_EQ(parser.pending_bytes(), bytes.size() - 1);
  parser.feed({bytes.data() + bytes.size() - 1, 1});
  ASSERT_TRUE(parser.next(f));
  EXPECT_EQ(unpack<GlobalPositionInt>(f)->hdg_cdeg, 9000);
}

TEST(Describe, NamesFieldsInWireOrderWithExactNumbers) {
  StatusText s;
  s.severity = 4;
  const std::string text = "PreArm: Need Position Estimate";
  std::copy(text.begin(), text.end(), s.text.begin());
  EXPECT_EQ(describe(pack(s, {})),
            "STATUSTEXT severity=4 text=PreArm: Need Position Estimate id=0 chunk_seq=0");
  Attitude a;
  a.roll_rad = 0.1f;
  const std::string d = describe(pack(a, {}));
  EXPECT_NE(d.find("roll=0.10000000149011612 "), std::string::npos) << d;  // float 0.1, exactly
  Frame other;
  other.msgid = 4;
  EXPECT_EQ(describe(other), "#4");
}

}  // namespace
}  // namespace swath::mavlink
