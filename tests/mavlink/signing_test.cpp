// MAVLink 2 signing (signing.hpp): SHA-256 against the FIPS 180-4 / NIST example vectors and
// against itself fed in random pieces; a signed frame is a frame the parser's checksum accepts
// (the incompat flag inside the checksum) with the signature the spec defines; the check accepts
// it once, and refuses it replayed, with one bit changed, with another key, a minute old, or
// unsigned. Key files: 32 raw bytes or 64 hex digits. The signing link between a ground station
// and a FakeCopter that signs: frames pass signed both ways; a frame with a wrong signature, a
// replayed one and an unsigned one are dropped; a vehicle with another key is never heard.
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "swath/base/input_error.hpp"
#include "swath/mavlink/copter_driver.hpp"
#include "swath/mavlink/endpoint.hpp"
#include "swath/mavlink/fake_copter.hpp"
#include "swath/mavlink/messages.hpp"
#include "swath/mavlink/signing.hpp"
#include "swath/mavlink/signing_link.hpp"

namespace swath::mavlink::signing_test {
namespace {

std::string hex(const Sha256Digest& d) {
  static const char* digits = "0123456789abcdef";
  std::string s;
  for (const std::uint8_t b : d) s += {digits[b >> 4], digits[b & 15]};
  return s;
}

std::string hash_text(const std::string& text) {
  return hex(sha256({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}));
}

TEST(Sha256, FipsExampleVectors) {
  EXPECT_EQ(hash_text("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(hash_text(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(hash_text("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(hash_text(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, PiecesOfAnySizeGiveTheOneShotDigest) {
  std::mt19937 random(20261129);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<std::uint8_t> data(std::uniform_int_distribution<int>(0, 300)(random));
    for (auto& b : data) b = static_cast<std::uint8_t>(random());
    Sha256 pieces;
    for (std::size_t at = 0; at < data.size();) {
      const std::size_t n = std::min<std::size_t>(data.size() - at, random() % 70);
      pieces.add({data.data() + at, n});
      at += n;
    }
    EXPECT_EQ(pieces.finish(), sha256(data)) << data.size() << " bytes";
  }
}

SigningKey test_key(std::uint8_t first = 1) {
  SigningKey k;
  for (std::size_t i = 0; i < k.secret.size(); ++i)
    k.secret[i] = static_cast<std::uint8_t>(first + i);
  return k;
}

std::vector<std::uint8_t> signed_heartbeat(const SigningKey& key, std::uint64_t timestamp,
                                           std::uint8_t link_id = 3) {
  const Frame f = pack(
      Heartbeat{.custom_mode = 4, .type = 2, .autopilot = 3, .base_mode = 1, .system_status = 4},
      FrameHeader{7, 1, 1});
  std::vector<std::uint8_t> bytes(kMaxFrameBytes);
  bytes.resize(serialize_signed(f, find_message(Heartbeat::kId)->crc_extra, key, link_id, timestamp,
                                bytes.data()));
  return bytes;
}

constexpr std::uint64_t kNow = 0x0000123456789AULL;  // a 48-bit timestamp, 10 µs units

TEST(Signing, ASignedFrameCarriesTheSpecsSignatureAndAGoodChecksum) {
  const SigningKey key = test_key();
  const std::vector<std::uint8_t> packet = signed_heartbeat(key, kNow);
  ASSERT_EQ(packet.size(), 10u + 9u + 2u + 13u);  // HEARTBEAT's payload is 9 bytes
  EXPECT_EQ(packet[2] & kIncompatSigned, kIncompatSigned);
  EXPECT_EQ(packet[21], 3);  // link id after the checksum
  std::uint64_t t = 0;
  for (int i = 0; i < 6; ++i) t |= std::uint64_t{packet[22 + i]} << (8 * i);
  EXPECT_EQ(t, kNow);
  // The signature by the spec's definition: SHA-256 over key, frame, link id, timestamp.
  std::vector<std::uint8_t> hashed(key.secret.begin(), key.secret.end());
  hashed.insert(hashed.end(), packet.begin(), packet.end() - 6);
  const Sha256Digest d = sha256(hashed);
  EXPECT_TRUE(std::equal(d.begin(), d.begin() + 6, packet.end() - 6));
  // The parser checks the checksum of a signed frame before it drops it: a good one counts as
  // signed_dropped, not bad_crc (the flag is inside the checksum).
  FrameParser parser;
  parser.feed(packet);
  Frame out;
  EXPECT_FALSE(parser.next(out));
  EXPECT_EQ(parser.stats().signed_dropped, 1u);
  EXPECT_EQ(parser.stats().bad_crc, 0u);
}

TEST(Signing, TheCheckAcceptsOnceAndRefusesReplaysChangesOtherKeysAndOldFrames) {
  const SigningKey key = test_key();
  SignatureCheck check(key);
  const auto first = signed_heartbeat(key, kNow);
  EXPECT_EQ(check.check(first, kNow), SignatureCheck::Verdict::accepted);
  EXPECT_EQ(check.check(first, kNow), SignatureCheck::Verdict::replayed);  // the same again
  EXPECT_EQ(check.check(signed_heartbeat(key, kNow - 5), kNow),
            SignatureCheck::Verdict::replayed);  // older than the last accepted
  EXPECT_EQ(check.check(signed_heartbeat(key, kNow + 1), kNow), SignatureCheck::Verdict::accepted);
  auto changed = signed_heartbeat(key, kNow + 2);
  changed[12] ^= 0x01;  // one payload bit
  EXPECT_EQ(check.check(changed, kNow), SignatureCheck::Verdict::bad_signature);
  EXPECT_EQ(check.check(signed_heartbeat(test_key(9), kNow + 3), kNow),
            SignatureCheck::Verdict::bad_signature);
  // A stream not heard before (another link id) whose timestamp is two minutes old.
  EXPECT_EQ(check.check(signed_heartbeat(key, kNow - 12000000, 4), kNow),
            SignatureCheck::Verdict::out_of_time);
  auto unsigned_frame = first;
  unsigned_frame[2] = 0;
  EXPECT_EQ(check.check(unsigned_frame, kNow), SignatureCheck::Verdict::not_signed);
}

TEST(Signing, KeyFilesAreThirtyTwoRawBytesOrSixtyFourHexDigits) {
  const std::string raw(32, '\x07');
  EXPECT_EQ(parse_signing_key(raw, "k").secret[31], 7);
  const SigningKey h =
      parse_signing_key("00112233445566778899aabbccddeeff00112233445566778899AABBCCDDEEFF\n", "k");
  EXPECT_EQ(h.secret[0], 0x00);
  EXPECT_EQ(h.secret[1], 0x11);
  EXPECT_EQ(h.secret[31], 0xFF);
  EXPECT_THROW(parse_signing_key(std::string(63, 'a'), "k"), base::InputError);
  EXPECT_THROW(parse_signing_key(std::string(64, 'g'), "k"), base::InputError);
  try {
    parse_signing_key("short", "key.txt");
  } catch (const base::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("key.txt: a signing key is 32 bytes"), std::string::npos);
  }
}

// Two ends of an in-memory wire: what one sends the other receives.
struct Wire {
  std::vector<std::uint8_t> to_a, to_b;
};
class WireEnd final : public Link {
 public:
  WireEnd(std::vector<std::uint8_t>& out, std::vector<std::uint8_t>& in) : out_(out), in_(in) {}
  void send(std::span<const std::uint8_t> bytes) override {
    out_.insert(out_.end(), bytes.begin(), bytes.end());
  }
  std::size_t receive(std::vector<std::uint8_t>& out) override {
    const std::size_t n = in_.size();
    out.insert(out.end(), in_.begin(), in_.end());
    in_.clear();
    return n;
  }

 private:
  std::vector<std::uint8_t>& out_;
  std::vector<std::uint8_t>& in_;
};

// A clock the test moves: signing timestamps in 10 µs units.
struct TestClock {
  std::uint64_t now = kNow;
  std::function<std::uint64_t()> fn() {
    return [this] { return now; };
  }
};

TEST(SigningLink, FramesPassSignedAndWrongReplayedOrUnsignedOnesAreDropped) {
  Wire wire;
  TestClock clock;
  const SigningKey key = test_key();
  SigningLink a(std::make_unique<WireEnd>(wire.to_b, wire.to_a), key, 1, clock.fn());
  SigningLink b(std::make_unique<WireEnd>(wire.to_a, wire.to_b), key, 2, clock.fn());
  Endpoint from(a, 255, 190), to(b, 1, 1);
  from.send(
      Heartbeat{.custom_mode = 0, .type = 6, .autopilot = 8, .base_mode = 0, .system_status = 4});
  const std::vector<std::uint8_t> on_the_wire = wire.to_b;  // what travelled, signed
  ASSERT_EQ(on_the_wire.size(), 10u + 9u + 2u + 13u);
  EXPECT_EQ(on_the_wire[2] & kIncompatSigned, kIncompatSigned);
  std::vector<Frame> got = to.receive();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].header.sysid, 255);
  EXPECT_EQ(unpack<Heartbeat>(got[0])->type, 6);
  // Replayed: the same bytes again.
  wire.to_b = on_the_wire;
  EXPECT_TRUE(to.receive().empty());
  EXPECT_EQ(b.counts().refused_replay, 1u);
  // A wrong signature: the frame signed with another key.
  wire.to_b = signed_heartbeat(test_key(9), clock.now + 100);
  EXPECT_TRUE(to.receive().empty());
  EXPECT_GE(b.counts().refused_signature, 1u);
  // Unsigned: the plain frame.
  const Frame plain = pack(Heartbeat{}, FrameHeader{0, 1, 1});
  wire.to_b = serialize(plain);
  EXPECT_TRUE(to.receive().empty());
  EXPECT_EQ(b.counts().refused_unsigned, 1u);
  // A later frame still passes, after the refusals, split across two reads.
  clock.now += 10;
  from.send(
      Heartbeat{.custom_mode = 0, .type = 6, .autopilot = 8, .base_mode = 0, .system_status = 3});
  const std::vector<std::uint8_t> second = wire.to_b;
  wire.to_b.assign(second.begin(), second.begin() + 7);
  EXPECT_TRUE(to.receive().empty());
  wire.to_b.assign(second.begin() + 7, second.end());
  got = to.receive();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(unpack<Heartbeat>(got[0])->system_status, 3);
  EXPECT_EQ(b.counts().accepted, 2u);
}

// A ground station's driver and a FakeCopter each over a signing link: with the same key the
// vehicle is heard and answers its commands; with another key it is never heard.
bool vehicle_heard(const SigningKey& gcs_key, const SigningKey& vehicle_key) {
  Wire wire;
  TestClock clock;
  SigningLink gcs(std::make_unique<WireEnd>(wire.to_b, wire.to_a), gcs_key, 1, clock.fn());
  SigningLink vehicle(std::make_unique<WireEnd>(wire.to_a, wire.to_b), vehicle_key, 2, clock.fn());
  FakeCopter fake(vehicle);
  CopterDriver driver(gcs, DriverSettings{});
  for (int k = 0; k <= 50; ++k) {
    const double t_s = 0.1 * k;
    clock.now = kNow + static_cast<std::uint64_t>(k) * 10000;  // 0.1 s
    fake.step(t_s);
    driver.poll(t_s);
  }
  return driver.state().link_alive && fake.gcs_heartbeats_received() > 0;
}

TEST(SigningLink, AFakeCopterThatSignsIsHeardOnlyWithTheSameKey) {
  EXPECT_TRUE(vehicle_heard(test_key(), test_key()));
  EXPECT_FALSE(vehicle_heard(test_key(), test_key(5)));
}

}  // namespace
}  // namespace swath::mavlink::signing_test
