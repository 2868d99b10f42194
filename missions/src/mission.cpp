// Mission readers (issue 45): QGC .plan, WPL 110 and Litchi CSV into one Mission value.
#include "swath/missions/mission.hpp"

#include "dji_kmz.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string_view>

#include "swath/base/csv_text.hpp"
#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/mavlink/commands.hpp"

namespace swath::missions {
namespace {

using base::InputError;
using geometry::GeoPoint;
using mavlink::Cmd;
using nlohmann::json;

constexpr int cmd(Cmd c) {
  return static_cast<int>(c);
}

// A UTF-8 byte order mark, which Windows editors put before a text file's first line.
constexpr std::string_view kBom = "\xEF\xBB\xBF";

std::size_t bom_size(std::string_view text) {
  return text.substr(0, kBom.size()) == kBom ? kBom.size() : 0;
}

// "QGC WPL 110" (Mission Planner, QGroundControl) or "QGC WPL 120" (older QGroundControl): one
// format, the same twelve fields a row.
bool is_wpl(std::string_view text) {
  text.remove_prefix(bom_size(text));
  return text.rfind("QGC WPL 110", 0) == 0 || text.rfind("QGC WPL 120", 0) == 0;
}

const json& member(const json& object, const char* key) {
  static const json null;
  const json* v = object.is_object() ? base::json_find(object, key) : nullptr;
  return v != nullptr ? *v : null;
}

// The place is `where` and `what` together, joined only for the message (a .plan has thousands of
// numbers, and a string made for each cost more than reading it).
double number(const json& j, const std::string& where, std::string_view what = {}) {
  if (!j.is_number() || !std::isfinite(j.get<double>()))
    throw InputError(where + std::string(what) + " must be a number");
  return j.get<double>();
}

// A fence circle's radius: a circle of none (or a negative one) fences nothing, and the check
// would pass a flight through the zone it was meant to be.
double checked_radius_m(double radius_m, const GeoPoint& centre, const std::string& where) {
  if (!(radius_m > 0) || !std::isfinite(radius_m))
    throw InputError(where + " at " + base::shortest_text(centre.lat_deg) + ", " +
                     base::shortest_text(centre.lon_deg) + ": radius " +
                     base::shortest_text(radius_m) + " m must be above 0");
  return radius_m;
}

GeoPoint checked_position(double lat_deg, double lon_deg, const std::string& where) {
  if (!(std::abs(lat_deg) <= 90 && std::abs(lon_deg) <= 180))
    throw InputError(where + ": latitude/longitude out of range (" + base::shortest_text(lat_deg) +
                     ", " + base::shortest_text(lon_deg) + ")");
  return {lat_deg, lon_deg, 0.0};
}

GeoPoint lat_lon(const json& pair, const std::string& where) {
  if (!pair.is_array() || pair.size() < 2)
    throw InputError(where + ": a position is [latitude, longitude]");
  return checked_position(number(pair[0], where, " latitude"), number(pair[1], where, " longitude"),
                          where);
}

AltitudeFrame altitude_frame_of(int frame, int command, const std::string& where) {
  if (!is_navigation(command)) return AltitudeFrame::none;
  switch (static_cast<mavlink::MavFrame>(frame)) {
    case mavlink::MavFrame::global:
    case mavlink::MavFrame::global_int:
      return AltitudeFrame::amsl;
    case mavlink::MavFrame::global_relative_alt:
    case mavlink::MavFrame::global_relative_alt_int:
      return AltitudeFrame::relative;
    case mavlink::MavFrame::global_terrain_alt:
    case mavlink::MavFrame::global_terrain_alt_int:
      return AltitudeFrame::terrain;
    default:
      throw InputError(where + ": frame " + std::to_string(frame) +
                       " is not a position frame (0 AMSL, 3 relative to home, 10 terrain)");
  }
}

// One item from MISSION_ITEM's fields; positions checked where the command flies to one.
Item make_item(int command, int frame, const std::array<double, 7>& p, std::string where) {
  Item item;
  item.command = command;
  item.frame = frame;
  item.altitude_frame = altitude_frame_of(frame, command, where);
  item.params = {p[0], p[1], p[2], p[3]};
  if (is_navigation(command)) {
    const double lat = std::isnan(p[4]) ? 0.0 : p[4], lon = std::isnan(p[5]) ? 0.0 : p[5];
    item.position = checked_position(lat, lon, where);
    if (!std::isfinite(p[6]) && command != cmd(Cmd::nav_land))
      throw InputError(where + ": the altitude (param 7) is missing");
    item.altitude_m = std::isfinite(p[6]) ? p[6] : 0.0;
  }
  item.place = std::move(where);
  return item;
}

int command_of(const json& item, const std::string& where) {
  const json& c = member(item, "command");
  if (!c.is_number_integer() || c.get<long long>() < 0 || c.get<long long>() > 65535)
    throw InputError(where + ": 'command' must be a MAV_CMD number");
  return static_cast<int>(c.get<long long>());
}

Item qgc_simple_item(const json& item, const std::string& where) {
  const int command = command_of(item, where);
  const json& frame = member(item, "frame");
  if (!frame.is_number_integer()) throw InputError(where + ": 'frame' must be a MAV_FRAME number");
  const json& params = member(item, "params");
  if (!params.is_array() || params.size() != 7)
    throw InputError(where + ": 'params' must hold 7 values");
  static constexpr std::array<std::string_view, 7> param_names = {
      ": params[0]", ": params[1]", ": params[2]", ": params[3]",
      ": params[4]", ": params[5]", ": params[6]"};
  std::array<double, 7> p{};
  for (std::size_t k = 0; k < 7; ++k)  // QGC writes unused params as null
    p[k] = params[k].is_null() ? std::nan("") : number(params[k], where, param_names[k]);
  return make_item(command, frame.get<int>(), p, where);
}

// A QGC complex item: its simple items when it carries them (a survey, a corridor scan), refused
// otherwise (a structure scan is generated by QGC at upload, not stored).
void add_complex_items(const json& item, const std::string& where, Mission& m) {
  const json& inner = member(member(item, "TransectStyleComplexItem"), "Items");
  if (!inner.is_array()) {
    const json& type = member(item, "complexItemType");
    throw InputError(where + ": the complex item '" +
                     (type.is_string() ? type.get<std::string>() : std::string("?")) +
                     "' carries no simple items to check; save the mission from QGroundControl "
                     "after converting it, or plan it with swath");
  }
  for (std::size_t k = 0; k < inner.size(); ++k)
    m.items.push_back(qgc_simple_item(inner[k], where + ", inner item " + std::to_string(k + 1)));
}

void read_qgc_fences(const json& root, const std::string& source, Mission& m) {
  const json& fence = member(root, "geoFence");
  const json& polygons = member(fence, "polygons");
  for (std::size_t i = 0; polygons.is_array() && i < polygons.size(); ++i) {
    const std::string where = source + ": geoFence polygon " + std::to_string(i + 1);
    std::vector<GeoPoint> ring;
    const json& points = member(polygons[i], "polygon");
    if (!points.is_array() || points.size() < 3)
      throw InputError(where + ": a fence polygon has at least 3 points");
    for (const json& p : points) ring.push_back(lat_lon(p, where));
    (member(polygons[i], "inclusion") == false ? m.exclusion_fences : m.inclusion_fences)
        .push_back(std::move(ring));
  }
  const json& circles = member(fence, "circles");
  for (std::size_t i = 0; circles.is_array() && i < circles.size(); ++i) {
    const std::string where = source + ": geoFence circle " + std::to_string(i + 1);
    const json& c = member(circles[i], "circle");
    const GeoPoint centre = lat_lon(member(c, "center"), where);
    const FenceCircle circle{
        centre, checked_radius_m(number(member(c, "radius"), where, ": radius"), centre, where)};
    (member(circles[i], "inclusion") == false ? m.exclusion_circles : m.inclusion_circles)
        .push_back(circle);
  }
  const json& rally = member(member(root, "rallyPoints"), "points");
  for (std::size_t i = 0; rally.is_array() && i < rally.size(); ++i)
    m.rally_points.push_back(lat_lon(rally[i], source + ": rally point " + std::to_string(i + 1)));
}

Mission parse_qgc(const json& root, const std::string& source) {
  Mission m;
  m.source = source;
  m.format = "QGC plan";
  const json& mission = member(root, "mission");
  if (!mission.is_object()) throw InputError(source + ": a QGC plan has a 'mission' object");
  const json& home = member(mission, "plannedHomePosition");
  if (!home.is_array() || home.size() != 3)
    throw InputError(source + ": mission.plannedHomePosition must be [lat, lon, alt]");
  m.home = lat_lon(home, source + ": plannedHomePosition");
  m.home_amsl_m = number(home[2], source + ": plannedHomePosition altitude");
  m.home_amsl_known = true;
  const json& firmware = member(mission, "firmwareType");  // MAV_AUTOPILOT
  if (firmware == 3) m.autopilot = Autopilot::ardupilot;
  if (firmware == 12) m.autopilot = Autopilot::px4;
  const bool multirotor = member(mission, "vehicleType") != 1;  // MAV_TYPE_FIXED_WING
  m.fixed_wing = !multirotor;
  const json& speed = member(mission, multirotor ? "hoverSpeed" : "cruiseSpeed");
  if (!speed.is_null()) m.cruise_speed_m_s = number(speed, source + ": mission speed");
  const json& items = member(mission, "items");
  if (!items.is_array()) throw InputError(source + ": mission.items must be a list");
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::string where = source + ": item " + std::to_string(i + 1);
    const json& type = member(items[i], "type");
    if (type == "ComplexItem")
      add_complex_items(items[i], where, m);
    else if (type == "SimpleItem")
      m.items.push_back(qgc_simple_item(items[i], where));
    else
      throw InputError(where + ": 'type' must be SimpleItem or ComplexItem");
  }
  read_qgc_fences(root, source, m);
  return m;
}

// A WPL 110 row: index, current, frame, command, param1-7, autocontinue.
struct WplRow {
  int frame = 0, command = 0;
  std::array<double, 7> params{};
  int line_no = 0;
  // "<source>: line N", made only for a message or an item's place (not for every row read).
  std::string where(const std::string& source) const {
    return source + ": line " + std::to_string(line_no);
  }
};

// A row's position, checked; its place named only when refused.
GeoPoint wpl_position(const WplRow& r, const std::string& source) {
  const double lat_deg = r.params[4], lon_deg = r.params[5];
  if (std::abs(lat_deg) <= 90 && std::abs(lon_deg) <= 180) return {lat_deg, lon_deg, 0.0};
  return checked_position(lat_deg, lon_deg, r.where(source));
}

std::vector<WplRow> wpl_rows(const std::string& text, const std::string& source) {
  std::size_t at = bom_size(text);
  std::string_view line;
  base::next_line(text, at, line);
  if (!is_wpl(line)) throw InputError(source + ": line 1: a WPL file starts with 'QGC WPL 110'");
  std::vector<WplRow> rows;
  for (int line_no = 2; base::next_line(text, at, line); ++line_no) {
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    const auto where = [&] { return source + ": line " + std::to_string(line_no); };
    // The fields as a stream reads them (white space between), without a stream per row.
    const std::vector<std::string_view> fields = base::whitespace_fields(line);
    std::array<double, 12> f{};
    for (std::size_t k = 0; k < f.size(); ++k) {
      if (k == fields.size())
        throw InputError(where() +
                         ": a WPL row has 12 fields (index, current, frame, command, 4 params, "
                         "latitude, longitude, altitude, autocontinue); found " +
                         std::to_string(k));
      // Params 1-4 (fields 5-8) may have no value, NaN (as a .plan's null); the rest may not.
      const bool may_be_nan = k >= 4 && k < 8;
      if (!base::parse_number(fields[k], f[k]) || std::isinf(f[k]) ||
          (std::isnan(f[k]) && !may_be_nan))
        throw InputError(where() + ": field " + std::to_string(k + 1) + " '" +
                         std::string(fields[k].substr(0, 40)) + "' is not a number");
    }
    WplRow r{static_cast<int>(f[2]), static_cast<int>(f[3]), {}, line_no};
    std::copy(f.begin() + 4, f.begin() + 11, r.params.begin());
    rows.push_back(std::move(r));
  }
  return rows;
}

Mission parse_wpl(const std::string& text, const std::string& source) {
  const std::vector<WplRow> rows = wpl_rows(text, source);
  if (rows.empty()) throw InputError(source + ": the WPL file has no home row");
  Mission m;
  m.source = source;
  m.format = "WPL 110";
  m.autopilot = Autopilot::ardupilot;  // Mission Planner's format: written for ArduPilot
  // Row 0 is home, its altitude above mean sea level (0: unknown to the writer).
  m.home = wpl_position(rows[0], source);
  m.home_amsl_m = rows[0].params[6];
  m.home_amsl_known = m.home_amsl_m != 0.0;
  for (std::size_t i = 1; i < rows.size(); ++i)
    m.items.push_back(make_item(rows[i].command, rows[i].frame, rows[i].params,
                                source + ": item " + std::to_string(i) + " (line " +
                                    std::to_string(rows[i].line_no) + ")"));
  return m;
}

// Litchi's columns by name (its Mission Hub's CSV), in any order.
struct LitchiColumns {
  std::map<std::string, std::size_t> index;
  std::size_t at(const std::string& name, const std::string& source) const {
    const auto it = index.find(name);
    if (it == index.end())
      throw InputError(source + ": line 1: the Litchi header has no column '" + name + "'");
    return it->second;
  }
  // A measure written in one of several units (Litchi's imperial export writes altitude(ft) and
  // speed(mph)): its column and the factor to metres or metres per second.
  std::pair<std::size_t, double> measure(
      const std::string& name, std::initializer_list<std::pair<const char*, double>> units,
      const std::string& source) const {
    for (const auto& [unit, factor] : units)
      if (const auto it = index.find(name + "(" + unit + ")"); it != index.end())
        return {it->second, factor};
    std::string names;
    for (const auto& [unit, factor] : units)
      names += std::string(names.empty() ? "" : " or ") + "'" + name + "(" + unit + ")'";
    throw InputError(source + ": line 1: the Litchi header has no column " + names);
  }
};

std::vector<std::string> split_commas(const std::string& line);

// Is the first line a CSV header naming latitude and longitude columns (a Litchi CSV's, in any
// order)?
bool is_litchi_header(std::string_view text) {
  if (text.empty() || text[0] == '{') return false;  // a JSON document: no line copied
  std::string line(text.substr(0, std::min<std::size_t>(text.find('\n'), 4096)));
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const auto header = split_commas(line);
  const auto has = [&](const char* name) {
    return std::find(header.begin(), header.end(), name) != header.end();
  };
  return has("latitude") && has("longitude");
}

std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> out(1);
  for (char c : line) {
    if (c == ',')
      out.emplace_back();
    else
      out.back().push_back(c);
  }
  return out;
}

std::array<double, 7> item_params(double p1, double p2, double p3, GeoPoint g, double alt) {
  return {p1, p2, p3, 0.0, g.lat_deg, g.lon_deg, alt};
}

// Litchi rows become MAVLink items: the waypoint (a stay action as its hold), a photo action,
// distance or time triggering on the leg the row starts (Litchi's photo_distinterval and
// photo_timeinterval hold to the next waypoint), and a speed change where the row's speed, the
// leg's to the next row, differs.
Mission parse_litchi(const std::string& text, const std::string& source) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  LitchiColumns columns;
  const auto header = split_commas(line);
  for (std::size_t k = 0; k < header.size(); ++k) columns.index[header[k]] = k;
  const std::size_t lat = columns.at("latitude", source), lon = columns.at("longitude", source),
                    mode = columns.at("altitudemode", source),
                    dist = columns.at("photo_distinterval", source),
                    time = columns.at("photo_timeinterval", source);
  const auto [alt, alt_to_m] = columns.measure("altitude", {{"m", 1.0}, {"ft", 0.3048}}, source);
  const auto [speed, speed_to_m_s] =
      columns.measure("speed", {{"m/s", 1.0}, {"km/h", 1 / 3.6}, {"mph", 0.44704}}, source);
  Mission m;
  m.source = source;
  m.format = "Litchi CSV";
  double speed_m_s = -1.0;
  bool distance_on = false, time_on = false;
  for (int line_no = 2; std::getline(in, line); ++line_no) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::string where = source + ": line " + std::to_string(line_no);
    const auto cells = split_commas(line);
    if (cells.size() != header.size())
      throw InputError(where + ": " + std::to_string(cells.size()) + " fields, the header has " +
                       std::to_string(header.size()));
    auto value = [&](std::size_t k) {
      double v = 0;
      if (!base::parse_number(cells[k], v) || !std::isfinite(v))
        throw InputError(where + ": " + header[k] + " '" + cells[k].substr(0, 40) +
                         "' is not a number");
      return v;
    };
    const GeoPoint g = checked_position(value(lat), value(lon), where);
    if (m.items.empty()) m.home = g;  // Litchi flies from where the drone stands
    const int frame = value(mode) == 1 ? 10 : 3;
    // A row's speed is its leg's to the next row (DJI's waypoint speed): a change after its
    // waypoint. The first row's also before it: the flight out to it is at that speed too.
    const double row_speed_m_s = value(speed) > 0 ? value(speed) * speed_to_m_s : -1.0;
    const auto set_speed = [&] {
      if (row_speed_m_s < 0 || row_speed_m_s == speed_m_s) return;
      speed_m_s = row_speed_m_s;
      m.items.push_back(
          make_item(cmd(Cmd::do_change_speed), 2, {1, speed_m_s, -1, 0, 0, 0, 0}, where));
    };
    if (m.items.empty()) set_speed();
    double hold_s = 0.0;
    bool photo = false;
    for (int a = 1; a <= 15; ++a) {
      const auto type = columns.index.find("actiontype" + std::to_string(a));
      const auto param = columns.index.find("actionparam" + std::to_string(a));
      if (type == columns.index.end() || param == columns.index.end()) break;
      if (value(type->second) == 0) hold_s += value(param->second) / 1000.0;
      if (value(type->second) == 1) photo = true;
    }
    m.items.push_back(make_item(cmd(Cmd::nav_waypoint), frame,
                                item_params(hold_s, 0, 0, g, value(alt) * alt_to_m), where));
    if (photo)
      m.items.push_back(make_item(cmd(Cmd::image_start_capture), 2, {0, 0, 1, 0, 0, 0, 0}, where));
    const double d = value(dist), t = value(time);
    if (d > 0 || distance_on) {
      m.items.push_back(
          make_item(cmd(Cmd::do_set_cam_trigg_dist), 2, {d > 0 ? d : 0, 0, 1, 0, 0, 0, 0}, where));
      distance_on = d > 0;
    }
    if (t > 0 || time_on) {
      const int c = cmd(t > 0 ? Cmd::image_start_capture : Cmd::image_stop_capture);
      m.items.push_back(make_item(c, 2, {0, t > 0 ? t : 0, 0, 0, 0, 0, 0}, where));
      time_on = t > 0;
    }
    set_speed();
  }
  if (m.items.empty()) throw InputError(source + ": the Litchi CSV has no waypoint row");
  return m;
}

}  // namespace

bool is_navigation(int command) {
  switch (static_cast<Cmd>(command)) {
    case Cmd::nav_waypoint:
    case Cmd::nav_loiter_turns:
    case Cmd::nav_loiter_time:
    case Cmd::nav_land:
    case Cmd::nav_takeoff:
      return true;
    default:
      return false;
  }
}

double above_home_m(const Item& item, std::optional<double> home_amsl_m,
                    double ground_above_home_m) {
  switch (item.altitude_frame) {
    case AltitudeFrame::amsl:
      if (!home_amsl_m)
        throw InputError(item.place +
                         ": the altitude is above mean sea level but the file gives no home "
                         "altitude (give the ground's heights, --terrain DEM)");
      return item.altitude_m - *home_amsl_m;
    case AltitudeFrame::terrain:
      return item.altitude_m + ground_above_home_m;
    default:
      return item.altitude_m;
  }
}

std::optional<double> home_amsl_m(const Mission& mission) {
  if (!mission.home_amsl_known) return std::nullopt;
  return mission.home_amsl_m;
}

Mission parse_mission(const std::string& text, const std::string& source) {
  if (is_wpl(text)) return parse_wpl(text, source);
  if (text.rfind("PK\x03\x04", 0) == 0) return parse_dji_kmz(text, source);
  const std::size_t bom = bom_size(text);
  if (is_litchi_header(std::string_view(text).substr(bom)))
    return bom ? parse_litchi(text.substr(bom), source) : parse_litchi(text, source);
  if (source.size() >= 4 && source.compare(source.size() - 4, 4, ".kmz") == 0)
    throw InputError(source + ": not a zip archive, which a DJI KMZ is (wpmz/waylines.wpml in it)");
  const std::size_t first = text.find_first_not_of(" \t\r\n", bom);
  if (first == std::string::npos || text[first] != '{')
    throw InputError(source +
                     ": neither a QGC plan (a JSON object), a QGC WPL 110 file ('QGC WPL 110' on "
                     "line 1), a Litchi CSV (a header naming latitude, longitude, altitude(m) "
                     "columns) nor a DJI KMZ (a zip archive)");
  const json root = bom ? base::parse_json_document(text.substr(bom), source)
                        : base::parse_json_document(text, source);
  if (member(root, "fileType") != "Plan")
    throw InputError(source +
                     ": neither a QGC plan (fileType \"Plan\"), a QGC WPL 110 file, a Litchi CSV "
                     "nor a DJI KMZ");
  return parse_qgc(root, source);
}

Mission read_mission(const std::string& path) {
  return parse_mission(base::read_text_file(path, "mission file"), path);
}

namespace {

// Commands of Mission Planner's fence and rally files: 5000 its fence return point, 5001-5004
// fence vertices and circles, 5100 rally points.
bool is_fence_or_rally(int command) {
  return (command >= 5000 && command <= cmd(Cmd::nav_fence_circle_exclusion)) ||
         command == cmd(Cmd::nav_rally_point);
}

}  // namespace

bool is_wpl_fence_file(const std::string& text) {
  if (!is_wpl(text)) return false;
  std::vector<WplRow> rows;
  try {
    rows = wpl_rows(text, "");
  } catch (const InputError&) {
    return false;  // read as a mission, whose reader names the problem
  }
  return !rows.empty() && std::all_of(rows.begin(), rows.end(),
                                      [](const WplRow& r) { return is_fence_or_rally(r.command); });
}

void add_wpl_fences(Mission& mission, const std::string& text, const std::string& source) {
  std::vector<GeoPoint> ring;
  int ring_command = 0;
  std::size_t ring_size = 0;
  for (const WplRow& r : wpl_rows(text, source)) {
    const GeoPoint g = wpl_position(r, source);
    // Mission Planner's fence return point: where a plane breaching the fence flies to. A copter
    // returns home (FENCE_ACTION), so the point is not flown and has nothing to check.
    if (r.command == 5000) continue;
    if (r.command == cmd(Cmd::nav_fence_polygon_vertex_inclusion) ||
        r.command == cmd(Cmd::nav_fence_polygon_vertex_exclusion)) {
      if (ring.empty()) {
        ring_command = r.command;
        ring_size = static_cast<std::size_t>(r.params[0]);
        if (ring_size < 3)
          throw InputError(r.where(source) + ": a fence polygon has at least 3 vertices");
      }
      ring.push_back(g);
      if (ring.size() == ring_size) {
        (ring_command == cmd(Cmd::nav_fence_polygon_vertex_inclusion) ? mission.inclusion_fences
                                                                      : mission.exclusion_fences)
            .push_back(ring);
        ring.clear();
      }
    } else if (r.command == cmd(Cmd::nav_fence_circle_inclusion)) {
      mission.inclusion_circles.push_back(
          {g, checked_radius_m(r.params[0], g, r.where(source) + ": fence circle")});
    } else if (r.command == cmd(Cmd::nav_fence_circle_exclusion)) {
      mission.exclusion_circles.push_back(
          {g, checked_radius_m(r.params[0], g, r.where(source) + ": fence circle")});
    } else if (r.command == cmd(Cmd::nav_rally_point)) {
      mission.rally_points.push_back(g);
    } else {
      throw InputError(r.where(source) + ": command " + std::to_string(r.command) +
                       " is no fence vertex, fence circle or rally point");
    }
  }
  if (!ring.empty())
    throw InputError(source + ": the last fence polygon has " + std::to_string(ring.size()) +
                     " of its " + std::to_string(ring_size) + " vertices");
}

}  // namespace swath::missions
