#pragma once
// Where a real vehicle is reached (docs/swath-fleet.md): the one URL grammar shared by
// `swath-fleet run --vehicles` and the fleet file's per-drone `mavlink {url, sysid}`. fleet keeps
// only the address (it opens no socket); swath::mavlink opens the link.

#include <cstdint>
#include <string>
#include <vector>

namespace swath::fleet {

struct VehicleAddress {
  bool tcp = false;          ///< false: UDP, listen on host:port; true: TCP, connect to host:port
  std::string host;          ///< a name or dotted address, non-empty
  std::uint16_t port = 0;    ///< 1..65535
  std::uint8_t sysid = 1;    ///< the vehicle's MAVLink system id, 1..255
  bool sysid_given = false;  ///< the text named it (/SYSID); else `sysid` is the caller's default
};

/// Reads `udp:HOST:PORT[/SYSID]` or `tcp:HOST:PORT[/SYSID]` (SYSID 1..255; absent: `default_sysid`,
/// 1..255) into `out`. Returns "" when it is one, else the problem as a phrase to follow the
/// quoted text ("is neither udp: nor tcp:", "has no HOST:PORT", "has a port that is not a number
/// in 1..65535", "has a system id that is not a number in 1..255").
std::string parse_vehicle_address(const std::string& text, std::uint8_t default_sysid,
                                  VehicleAddress& out);

/// `udp:HOST:PORT` or `tcp:HOST:PORT` (without the system id): what summary.json records.
std::string vehicle_address_text(const VehicleAddress& a);

/// A comma-separated list of addresses (`--vehicles`), each without /SYSID taking its place in
/// the list plus 1 (SITL's SYSID_THISMAV = instance + 1). Throws base::InputError with one
/// sentence naming the bad entry.
std::vector<VehicleAddress> parse_vehicle_addresses(const std::string& list);

}  // namespace swath::fleet
