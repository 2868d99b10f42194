// DJI WPML KMZ (DJI Pilot 2): wpmz/waylines.wpml, the file the aircraft executes, read into the
// same Mission as a MAVLink file (issue 45).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <memory>
#include <optional>
#include <pugixml.hpp>

#include "dji_kmz.hpp"
#include "libzip.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/mavlink/commands.hpp"
#include "swath/missions/writers.hpp"

namespace swath::missions {
namespace {

using base::InputError;
using mavlink::Cmd;

// The bytes of one entry of an in-memory zip archive.
std::string zip_entry(const std::string& bytes, const char* name, const std::string& source) {
  const LibZip& z = libzip();
  zip_error_t error;
  z.zip_error_init(&error);
  zip_source_t* memory = z.zip_source_buffer_create(bytes.data(), bytes.size(), 0, &error);
  zip_t* archive = memory ? z.zip_open_from_source(memory, ZIP_RDONLY, &error) : nullptr;
  if (archive == nullptr) {
    if (memory) z.zip_source_free(memory);
    throw InputError(source + ": not a readable zip archive (a DJI KMZ)");
  }
  std::unique_ptr<zip_t, decltype(&::zip_discard)> guard(archive, z.zip_discard);
  zip_stat_t stat;
  zip_file_t* file =
      z.zip_stat(archive, name, 0, &stat) == 0 ? z.zip_fopen(archive, name, 0) : nullptr;
  if (file == nullptr) throw InputError(source + ": the KMZ has no " + name);
  std::string out(stat.size, '\0');
  const zip_int64_t read = z.zip_fread(file, out.data(), stat.size);
  z.zip_fclose(file);
  if (read < 0 || static_cast<zip_uint64_t>(read) != stat.size)
    throw InputError(source + ": " + name + " cannot be read from the KMZ");
  return out;
}

double number(const pugi::xml_node& node, const char* name, const std::string& where) {
  double v = 0;
  const std::string text = node.child(name).text().get();
  if (!base::parse_number(text, v) || !std::isfinite(v))
    throw InputError(where + ": wpml:" + std::string(name).substr(5) + " '" + text.substr(0, 40) +
                     "' is not a number");
  return v;
}

int frame_of(const std::string& mode, const std::string& where) {
  if (mode == "relativeToStartPoint") return 3;
  if (mode == "WGS84") return 0;  // ellipsoidal heights, read as above mean sea level
  if (mode == "realTimeFollowSurface") return 10;
  throw InputError(where + ": executeHeightMode '" + mode +
                   "' is not read (relativeToStartPoint, WGS84, realTimeFollowSurface)");
}

Item command(Cmd c, double p1, double p2, const std::string& where) {
  Item item;
  item.command = static_cast<int>(c);
  item.frame = 2;
  item.params = {p1, p2, 0, 0};
  item.place = where;
  return item;
}

// Photos every distance or interval from a group's first waypoint to its last; `index` holds,
// for each of the wayline's waypoints, the position in m.items just after it.
void add_triggers(const pugi::xml_node& folder, const std::string& in,
                  const std::vector<std::size_t>& index, Mission& m) {
  std::vector<std::pair<std::size_t, Item>> inserts;
  for (const pugi::xml_node& p : folder.children("Placemark"))
    for (const pugi::xml_node& g : p.children("wpml:actionGroup")) {
      const std::string type =
          g.child("wpml:actionTrigger").child("wpml:actionTriggerType").text().get();
      if (type != "multipleDistance" && type != "multipleTiming") continue;
      const std::string where = in + ": action group " + g.child("wpml:actionGroupId").text().get();
      const double start = number(g, "wpml:actionGroupStartIndex", where);
      const double end = number(g, "wpml:actionGroupEndIndex", where);
      const double value = number(g.child("wpml:actionTrigger"), "wpml:actionTriggerParam", where);
      if (!(start >= 0 && end >= start && end < static_cast<double>(index.size())))
        throw InputError(where + ": its waypoint indices are out of range");
      const bool distance = type == "multipleDistance";
      inserts.push_back({index[static_cast<std::size_t>(start)],
                         distance ? command(Cmd::do_set_cam_trigg_dist, value, 0, where)
                                  : command(Cmd::image_start_capture, 0, value, where)});
      inserts.push_back({index[static_cast<std::size_t>(end)],
                         distance ? command(Cmd::do_set_cam_trigg_dist, 0, 0, where)
                                  : command(Cmd::image_stop_capture, 0, 0, where)});
    }
  std::stable_sort(inserts.begin(), inserts.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto it = inserts.rbegin(); it != inserts.rend(); ++it)
    m.items.insert(m.items.begin() + static_cast<std::ptrdiff_t>(it->first), it->second);
}

// A missionConfig height (metres above the take-off point) when the file gives one.
std::optional<double> config_height_m(const pugi::xml_node& config, const char* name,
                                      const std::string& in) {
  if (config.child(name).empty()) return std::nullopt;
  const double h = number(config, name, in + ": missionConfig");
  if (h < 0)
    throw InputError(in + ": missionConfig: wpml:" + std::string(name).substr(5) + " " +
                     base::shortest_text(h) + " m is below the take-off point");
  return h;
}

// The seconds the aircraft hovers on reaching placemark `p` (number `k` of its wayline): the
// hoverTime of each hover action in its reachPoint action groups that start and end on it (DJI
// Pilot 2 stops there for that long, as a .plan's held waypoint or a Litchi stay). A group over
// several points is not read as a hold (no stop is taken for granted).
double hover_s(const pugi::xml_node& p, std::size_t k, const std::string& where) {
  double hold_s = 0.0;
  for (const pugi::xml_node& g : p.children("wpml:actionGroup")) {
    if (std::string(g.child("wpml:actionTrigger").child("wpml:actionTriggerType").text().get()) !=
        "reachPoint")
      continue;
    const std::string in = where + ": action group " + g.child("wpml:actionGroupId").text().get();
    const double start = number(g, "wpml:actionGroupStartIndex", in);
    const double end = number(g, "wpml:actionGroupEndIndex", in);
    if (start != static_cast<double>(k) || end != start) continue;
    for (const pugi::xml_node& a : g.children("wpml:action"))
      if (std::string(a.child("wpml:actionActuatorFunc").text().get()) == "hover") {
        const double t = number(a.child("wpml:actionActuatorFuncParam"), "wpml:hoverTime", in);
        if (t > 0) hold_s += t;
      }
  }
  return hold_s;
}

// One wayline (a Folder) appended to `m`: its waypoints, speeds and photo triggers. `speed` is
// the speed in force, carried from one wayline to the next as the aircraft flies them in turn.
void add_wayline(const pugi::xml_node& folder, const std::string& in, Mission& m, double& speed) {
  const int frame = frame_of(folder.child("wpml:executeHeightMode").text().get(), in);
  std::vector<std::size_t> index;  // placemark -> items position
  for (const pugi::xml_node& p : folder.children("Placemark")) {
    const std::string where = in + ": waypoint " + std::to_string(index.size());
    double lon = 0, lat = 0;
    if (std::sscanf(p.child("Point").child("coordinates").text().get(), " %lf , %lf", &lon, &lat) !=
            2 ||
        !(std::abs(lat) <= 90 && std::abs(lon) <= 180))
      throw InputError(where + ": coordinates must be 'longitude,latitude'");
    // A waypoint's speed is its leg's to the next (DJI's waypointSpeed): a change after it; the
    // first one's also before it, the flight out to it being at that speed too. The aircraft
    // flies no slower than kDjiMinSpeed_m_s: a slower one is read as that (and overruns a stop
    // by as much).
    const double written = number(p, "wpml:waypointSpeed", where);
    const double v = written > 0 ? std::max(written, kDjiMinSpeed_m_s) : written;
    const auto set_speed = [&] {
      if (v > 0 && v != speed)
        m.items.push_back(command(Cmd::do_change_speed, 1, speed = v, where));
    };
    if (index.empty()) set_speed();
    Item w;
    w.command = static_cast<int>(Cmd::nav_waypoint);
    w.frame = frame;
    w.altitude_frame = frame == 3   ? AltitudeFrame::relative
                       : frame == 0 ? AltitudeFrame::amsl
                                    : AltitudeFrame::terrain;
    w.position = {lat, lon, 0.0};
    w.altitude_m = number(p, "wpml:executeHeight", where);
    w.place = where;
    // A hover on arrival is a hold (param1): the aircraft is at rest there.
    w.params[0] = hover_s(p, index.size(), where);
    m.items.push_back(w);
    index.push_back(m.items.size());
    set_speed();
  }
  if (index.empty()) throw InputError(in + ": no Placemark (waypoint)");
  add_triggers(folder, in, index, m);
}

// The aircraft climbs to the take-off security height over its take-off point before it flies to
// the first waypoint, however low that is: a NAV_TAKEOFF there, in place (0, 0: where it is).
void add_take_off(const pugi::xml_node& config, const std::string& in, Mission& m) {
  const auto climb_m = config_height_m(config, "wpml:takeOffSecurityHeight", in);
  if (!climb_m) return;
  Item take_off = command(Cmd::nav_takeoff, 0, 0, in + ": takeOffSecurityHeight");
  take_off.frame = 3;
  take_off.altitude_frame = AltitudeFrame::relative;
  take_off.altitude_m = *climb_m;
  const auto first = std::find_if(m.items.begin(), m.items.end(), [](const Item& item) {
    return item.command == static_cast<int>(Cmd::nav_waypoint);
  });
  m.items.insert(first, take_off);
}

}  // namespace

Mission parse_dji_kmz(const std::string& bytes, const std::string& source) {
  const std::string wpml = zip_entry(bytes, "wpmz/waylines.wpml", source);
  pugi::xml_document doc;
  if (!doc.load_string(wpml.c_str())) throw InputError(source + ": wpmz/waylines.wpml is not XML");
  const pugi::xml_node document = doc.child("kml").child("Document");
  const pugi::xml_node config = document.child("wpml:missionConfig");
  const std::string in = source + ": waylines.wpml";
  Mission m;
  m.source = source;
  m.format = "DJI WPML";
  const std::size_t waylines = static_cast<std::size_t>(
      std::distance(document.children("Folder").begin(), document.children("Folder").end()));
  // Each Folder is a wayline; the aircraft flies them one after another, in the file's order.
  double speed = -1;
  std::size_t k = 0;
  for (const pugi::xml_node& folder : document.children("Folder")) {
    add_wayline(folder, waylines > 1 ? in + ": wayline " + std::to_string(k) : in, m, speed);
    ++k;
  }
  if (waylines == 0) throw InputError(in + ": no Folder (wayline)");
  // DJI flies from where the aircraft stands: taken as the first waypoint.
  for (const Item& item : m.items)
    if (item.command == static_cast<int>(Cmd::nav_waypoint)) {
      m.home = item.position;
      break;
    }
  add_take_off(config, in, m);
  const std::string finish = config.child("wpml:finishAction").text().get();
  m.items.push_back(command(finish == "autoLand" ? Cmd::nav_land : Cmd::nav_return_to_launch, 0, 0,
                            in + ": finishAction " + finish));
  // goHome climbs to the RTH height when below it (DJI's return to home).
  m.return_altitude_m = config_height_m(config, "wpml:globalRTHHeight", in);
  return m;
}

}  // namespace swath::missions
