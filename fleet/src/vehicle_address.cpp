#include "swath/fleet/vehicle_address.hpp"

#include <algorithm>
#include <charconv>

#include "swath/base/input_error.hpp"

namespace swath::fleet {

namespace {

// An integer in [lo, hi] spelled with digits only (no sign, no space, no trailing text).
bool whole_number(const std::string& s, int lo, int hi, int& v) {
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  return ec == std::errc() && p == s.data() + s.size() && v >= lo && v <= hi;
}

}  // namespace

std::string parse_vehicle_address(const std::string& text, std::uint8_t default_sysid,
                                  VehicleAddress& out) {
  VehicleAddress a;
  std::string rest;
  if (text.rfind("udp:", 0) == 0) {
    rest = text.substr(4);
  } else if (text.rfind("tcp:", 0) == 0) {
    a.tcp = true;
    rest = text.substr(4);
  } else {
    return "is neither udp: nor tcp:";
  }
  a.sysid = default_sysid;
  if (const std::size_t slash = rest.find('/'); slash != std::string::npos) {
    int v = 0;
    if (!whole_number(rest.substr(slash + 1), 1, 255, v))
      return "has a system id that is not a number in 1..255";
    a.sysid = static_cast<std::uint8_t>(v);
    a.sysid_given = true;
    rest = rest.substr(0, slash);
  }
  const std::size_t colon = rest.rfind(':');
  if (colon == std::string::npos || colon == 0) return "has no HOST:PORT";
  a.host = rest.substr(0, colon);
  int v = 0;
  if (!whole_number(rest.substr(colon + 1), 1, 65535, v))
    return "has a port that is not a number in 1..65535";
  a.port = static_cast<std::uint16_t>(v);
  out = a;
  return "";
}

std::string vehicle_address_text(const VehicleAddress& a) {
  return std::string(a.tcp ? "tcp:" : "udp:") + a.host + ":" + std::to_string(a.port);
}

std::vector<VehicleAddress> parse_vehicle_addresses(const std::string& list) {
  std::vector<VehicleAddress> out;
  std::size_t begin = 0;
  while (begin <= list.size()) {
    const std::size_t comma = std::min(list.find(',', begin), list.size());
    const std::string item = list.substr(begin, comma - begin);
    begin = comma + 1;
    if (item.empty()) {
      if (comma == list.size()) break;
      continue;
    }
    const auto bad = [&](const std::string& why) {
      return base::InputError("--vehicles: \"" + item + "\" " + why +
                              " (use udp:HOST:PORT or tcp:HOST:PORT, optionally /SYSID)");
    };
    VehicleAddress u;
    const std::string why = parse_vehicle_address(
        item, static_cast<std::uint8_t>(std::min<std::size_t>(out.size() + 1, 255)), u);
    if (!why.empty()) throw bad(why);
    out.push_back(u);
  }
  if (out.empty()) throw base::InputError("--vehicles names no vehicle");
  return out;
}

}  // namespace swath::fleet
