// swath's MAVLink codec against an independent one: npm's node-mavlink 2.3.0 (docs/swath-fleet.md),
// run by tests/mavlink/oracle/decode.cjs. scripts/setup installs it into .oracles/; these tests
// fail (not skip) without it, naming the command that installs it.
//   - CRC_EXTRA and payload length of each of swath's messages equal node-mavlink's table;
//   - node-mavlink decodes frames swath encoded (random values, truncated payloads, MAVLink 1)
//     to the same field values;
//   - one PARAM_REQUEST_READ, PARAM_VALUE and COMMAND_INT as the drivers send them decode alike;
//   - swath decodes the capture node-mavlink ships (3,398 MAVLink 2 frames from a PX4 flight)
//     frame for frame as node-mavlink does, skipping exactly the frames of other messages.
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "mavlink_test_support.hpp"
#include "swath/mavlink/commands.hpp"
#include "swath/mavlink/frame.hpp"
#include "swath/mavlink/messages.hpp"

namespace swath::mavlink {
namespace {

const std::string kOracleModules = SWATH_ORACLE_DIR "/node_modules";
const std::string kScript = SWATH_SOURCE_DIR "/tests/mavlink/oracle/decode.cjs";

// Runs the oracle; its standard output, or a failure naming how to get it.
std::string oracle(const std::string& args) {
  if (!std::filesystem::exists(kOracleModules + "/node-mavlink/package.json")) {
    ADD_FAILURE() << "node-mavlink is not installed in " << kOracleModules
                  << ": run scripts/setup (it installs nodejs, npm and the oracle)";
    return "";
  }
  const std::string command = "node '" + kScript + "' '" + kOracleModules + "' " + args;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) {
    ADD_FAILURE() << "cannot run " << command;
    return "";
  }
  std::string out;
  char buf[65536];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  const int status = pclose(pipe);
  EXPECT_EQ(status, 0) << command;
  return out;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string known_ids() {
  std::string ids;
  for (const MessageInfo& m : known_messages()) ids += " " + std::to_string(m.id);
  return ids;
}

// One field's value as text from both sides; numbers compare as numbers (JavaScript and C++
// print the same double differently), integers exactly as text, strings as written.
struct FieldValues {
  std::vector<std::string> names;
  std::vector<std::vector<std::string>> values;  // one entry per array element
  std::vector<bool> floating;
  std::vector<bool> text;
};

struct Collector {
  FieldValues& out;
  template <class E>
  static std::string number(E v) {
    if constexpr (std::is_floating_point_v<E>) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.17g", static_cast<double>(v));
      return buf;
    } else {
      return std::to_string(+v);
    }
  }
  template <class T>
  void field(const T& value, std::string_view name) {
    using Shape = detail::FieldShape<T>;
    using E = typename Shape::Element;
    out.names.emplace_back(name);
    out.floating.push_back(std::is_floating_point_v<E>);
    out.text.push_back(std::is_same_v<E, char>);
    std::vector<std::string> v;
    if constexpr (Shape::count == 0) {
      v.push_back(number<E>(value));
    } else if constexpr (std::is_same_v<E, char>) {
      v.emplace_back(value.data(), std::find(value.begin(), value.end(), '\0'));
    } else {
      for (const E& e : value) v.push_back(number<E>(e));
    }
    out.values.push_back(v);
  }
  template <class T>
  void extension(const T& value, std::string_view name) {
    field(value, name);
  }
};

FieldValues ours(const Frame& frame) {
  FieldValues values;
  for_each_message([&](auto sample) {
    using M = decltype(sample);
    if (frame.msgid != M::kId) return;
    M m = *unpack<M>(frame);
    Collector c{values};
    m.fields(c);
  });
  return values;
}

bool same_number(const std::string& mine, const std::string& node, bool floating) {
  if (!floating) return mine == node;
  const double a = std::strtod(mine.c_str(), nullptr);
  const double b = std::strtod(node.c_str(), nullptr);  // "nan", "inf", "-inf" read as such
  return (std::isnan(a) && std::isnan(b)) || a == b;
}

// Compares node's "... | NAME f1=v1 f2=v2 ..." with our frame, field by field in wire order (a
// field's text runs to the next " name=", so text with spaces is fine).
void expect_same_fields(const Frame& frame, const std::string& node_line,
                        const std::string& where) {
  const FieldValues mine = ours(frame);
  const std::size_t bar = node_line.find(" | ");
  ASSERT_NE(bar, std::string::npos) << where << ": " << node_line;
  std::string rest = node_line.substr(bar + 3);
  const MessageInfo* info = find_message(frame.msgid);
  ASSERT_EQ(rest.substr(0, info->name.size()), info->name) << where;
  rest = rest.substr(info->name.size());
  for (std::size_t i = 0; i < mine.names.size(); ++i) {
    const std::string key = " " + mine.names[i] + "=";
    ASSERT_EQ(rest.rfind(key, 0), 0u) << where << ": expected " << key << " in" << rest;
    std::size_t end = rest.size();
    if (i + 1 < mine.names.size()) end = rest.find(" " + mine.names[i + 1] + "=", key.size());
    ASSERT_NE(end, std::string::npos) << where;
    std::string value = rest.substr(key.size(), end - key.size());
    rest = rest.substr(end);
    std::vector<std::string> node_values;
    if (mine.text[i] || value.empty() || value.front() != '[') {
      node_values.push_back(value);
    } else {
      std::istringstream in(value.substr(1, value.size() - 2));
      for (std::string item; std::getline(in, item, ',');) node_values.push_back(item);
    }
    ASSERT_EQ(node_values.size(), mine.values[i].size()) << where << " " << mine.names[i];
    for (std::size_t k = 0; k < node_values.size(); ++k) {
      const bool same = mine.text[i]
                            ? node_values[k] == mine.values[i][k]
                            : same_number(mine.values[i][k], node_values[k], mine.floating[i]);
      EXPECT_TRUE(same) << where << " " << info->name << "." << mine.names[i] << ": swath "
                        << mine.values[i][k] << ", node-mavlink " << node_values[k];
    }
  }
  EXPECT_TRUE(rest.empty()) << where << ": node-mavlink has more fields:" << rest;
}

// node-mavlink's lines for `frames` written one after the other to the temporary file `name`
// (one per test: ctest runs tests in parallel); `ids`: the message ids it is to decode (" 20 22").
std::vector<std::string> oracle_lines(const std::vector<Frame>& frames, const std::string& ids,
                                      const std::string& name) {
  std::vector<std::uint8_t> bytes;
  for (const Frame& f : frames) {
    const auto b = serialize(f);
    bytes.insert(bytes.end(), b.begin(), b.end());
  }
  const std::string path =
      (std::filesystem::temp_directory_path() / (name + "-" + std::to_string(getpid()) + ".bin"))
          .string();
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  const auto lines = lines_of(oracle("frames '" + path + "'" + ids));
  std::filesystem::remove(path);
  return lines;
}

std::string header_text(const Frame& f) {
  return std::to_string(f.version) + " " + std::to_string(f.header.seq) + " " +
         std::to_string(f.header.sysid) + " " + std::to_string(f.header.compid) + " " +
         std::to_string(f.msgid);
}

TEST(NodeMavlink, CrcExtraAndLengthsEqualItsTable) {
  const auto lines = lines_of(oracle("crc" + known_ids()));
  const auto messages = known_messages();
  ASSERT_EQ(lines.size(), messages.size());
  for (std::size_t i = 0; i < messages.size(); ++i) {
    std::istringstream in(lines[i]);
    std::uint32_t id;
    std::string name;
    int crc;
    in >> id >> name >> crc;
    EXPECT_EQ(id, messages[i].id);
    EXPECT_EQ(name, messages[i].name);
    EXPECT_EQ(crc, messages[i].crc_extra) << name;  // a field's name, type, order or count
  }
}

TEST(NodeMavlink, DecodesFramesSwathEncodedToTheSameValues) {
  std::mt19937_64 rng(2026);
  std::vector<Frame> frames;
  for (int i = 0; i < 600; ++i)
    frames.push_back(test::random_frame(rng, static_cast<std::uint8_t>(i)));
  const auto lines = oracle_lines(frames, known_ids(), "swath-mavlink-oracle");
  ASSERT_EQ(lines.size(), frames.size()) << "node-mavlink accepted a different number of frames";
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const std::string where = "frame " + std::to_string(i);
    EXPECT_EQ(lines[i].substr(0, lines[i].find(" | ")), header_text(frames[i])) << where;
    expect_same_fields(frames[i], lines[i], where);
  }
}

// The messages of the safety check at connect and of the PX4 driver's go-to, one of each as the
// drivers and fakes send them (a 16-character name with no NUL, PX4's bytewise INT32, a NaN yaw),
// decoded by node-mavlink to the same values; their CRC_EXTRA as in its table.
TEST(NodeMavlink, ParameterMessagesAndCommandIntAsTheDriversSendThem) {
  ParamRequestRead read;
  read.target_system = 1;
  read.target_component = 1;
  const std::string name = "FS_GCS_ENABLE";
  std::copy(name.begin(), name.end(), read.param_id.begin());
  ParamValue value;
  const std::string full = "SIXTEEN_CHARS_ID";  // exactly 16: no NUL on the wire
  std::copy(full.begin(), full.end(), value.param_id.begin());
  value.param_value = std::bit_cast<float>(std::int32_t{2});
  value.param_type = kParamTypeInt32;
  value.param_count = 1200;
  value.param_index = 417;
  CommandInt go;
  go.command = static_cast<std::uint16_t>(Cmd::do_reposition);
  go.frame = kFrameGlobalRelativeAltInt;
  go.param1 = -1;
  go.param2 = kRepositionChangeMode;
  go.param4 = std::numeric_limits<float>::quiet_NaN();
  go.x = 473977420;
  go.y = 85455940;
  go.z = 20;
  go.target_system = 1;
  go.target_component = 1;
  const std::vector<Frame> frames{pack(read, FrameHeader{0, 255, 190}),
                                  pack(value, FrameHeader{1, 1, 1}),
                                  pack(go, FrameHeader{2, 255, 190})};
  const auto lines = oracle_lines(frames, " 20 22 75", "swath-mavlink-oracle-params");
  ASSERT_EQ(lines.size(), frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(lines[i].substr(0, lines[i].find(" | ")), header_text(frames[i]));
    expect_same_fields(frames[i], lines[i], "frame " + std::to_string(i));
  }
  const auto crc = lines_of(oracle("crc 20 22 75"));
  ASSERT_EQ(crc.size(), 3u);
  EXPECT_EQ(crc[0], "20 PARAM_REQUEST_READ " + std::to_string(crc_extra<ParamRequestRead>()));
  EXPECT_EQ(crc[1], "22 PARAM_VALUE " + std::to_string(crc_extra<ParamValue>()));
  EXPECT_EQ(crc[2], "75 COMMAND_INT " + std::to_string(crc_extra<CommandInt>()));
}

TEST(NodeMavlink, TheCaptureItShipsIsDecodedAlike) {
  const std::string capture = lines_of(oracle("capture")).at(0);
  std::ifstream in(capture, std::ios::binary);
  ASSERT_TRUE(in) << capture;
  const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), {}};
  const auto node_lines = lines_of(oracle("frames '" + capture + "'" + known_ids()));
  ASSERT_GT(node_lines.size(), 3000u);

  FrameParser parser;
  parser.feed(bytes);
  parser.finish();
  std::vector<Frame> frames;
  for (Frame f; parser.next(f);) frames.push_back(f);
  std::vector<std::string> node_known;  // node's frames of swath's messages, in order
  for (const std::string& line : node_lines)
    if (line.find(" | ") != std::string::npos) node_known.push_back(line);
  ASSERT_EQ(frames.size(), node_known.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const std::string where = "capture frame " + std::to_string(i);
    EXPECT_EQ(node_known[i].substr(0, node_known[i].find(" | ")), header_text(frames[i])) << where;
    expect_same_fields(frames[i], node_known[i], where);
  }
  const ParserStats& s = parser.stats();
  // Every frame of the capture is one of swath's messages or skipped whole as unknown; node-mavlink
  // drops the 14 frames of messages missing from its registry (LINK_NODE_STATUS,
  // CURRENT_EVENT_SEQUENCE of the development dialect).
  EXPECT_EQ(s.frames + s.unknown_id, node_lines.size() + 14);
  EXPECT_EQ(parser.pending_bytes(), 0u);
  EXPECT_EQ(s.bad_crc, 0u);
  EXPECT_EQ(s.bytes_skipped, 0u);
  EXPECT_EQ(s.bytes_in_frames + s.bytes_unknown, bytes.size());
}

}  // namespace
}  // namespace swath::mavlink
