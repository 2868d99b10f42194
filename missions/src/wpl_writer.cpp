// WPL 110 writers (Mission Planner): missions, ArduPilot polygon fences and rally points, and the
// legacy .fen fence list; read back by mission.cpp (parse_mission, add_wpl_fences).
#include <cmath>

#include "swath/base/number_text.hpp"
#include "swath/mavlink/commands.hpp"
#include "swath/missions/writers.hpp"

namespace swath::missions {
namespace {

using mavlink::Cmd;
using mavlink::MavFrame;

constexpr int number(Cmd c) {
  return static_cast<int>(c);
}

constexpr int number(MavFrame f) {
  return static_cast<int>(f);
}

// A row: index, current, frame, command, seven params (latitude and longitude to 1e-9 degrees,
// the others to 1e-6), autocontinue 1. Appended to `out` (no string per row or number). A value
// that is none (NaN, a .plan's null) is 0, or with `nan_params` in params 1-4 "NaN": PX4 reads a
// yaw of 0 as north, NaN as the yaw left as it is, and QGroundControl's WPL reader
// (QString::toDouble: letters lower-cased, then "nan") reads "NaN" back as NaN.
void append_wpl_row(std::string& out, std::size_t index, int current, int frame, int command,
                    const std::array<double, 7>& p, bool nan_params = false) {
  base::append_integer_text(out, index);
  out += '\t';
  base::append_integer_text(out, current);
  out += '\t';
  base::append_integer_text(out, frame);
  out += '\t';
  base::append_integer_text(out, command);
  for (std::size_t k = 0; k < 7; ++k) {
    out += '\t';
    if (nan_params && k < 4 && std::isnan(p[k]))
      out += "NaN";
    else
      base::append_fixed_text(out, std::isnan(p[k]) ? 0.0 : p[k], k == 4 || k == 5 ? 9 : 6);
  }
  out += "\t1\n";
}

std::array<double, 7> params_of(const Item& item) {
  return {item.params[0],        item.params[1],        item.params[2], item.params[3],
          item.position.lat_deg, item.position.lon_deg, item.altitude_m};
}

}  // namespace

std::string write_wpl(const Mission& mission) {
  const geometry::GeoPoint& home = mission.home;
  std::string out = "QGC WPL 110\n";
  // Row 0 is the home, above mean sea level (0 when swath does not know the ground there).
  append_wpl_row(out, 0, 1, number(MavFrame::global), number(Cmd::nav_waypoint),
                 {0, 0, 0, 0, home.lat_deg, home.lon_deg, mission.home_amsl_m});
  std::size_t index = 1;
  // ArduPilot's files keep 0 for no value (the files swath has always written for it).
  const bool nan_params = mission.autopilot == Autopilot::px4;
  for (const Item& item : mission.items)
    append_wpl_row(out, index++, 0, item.frame, item.command, params_of(item), nan_params);
  return out;
}

std::string write_wpl_fences(const Mission& mission) {
  // param1 is the polygon's vertex count, repeated on each of its vertices.
  std::string out = "QGC WPL 110\n";
  std::size_t index = 0;
  auto polygon = [&](const std::vector<geometry::GeoPoint>& ring, Cmd command) {
    for (const geometry::GeoPoint& g : ring)
      append_wpl_row(out, index++, 0, number(MavFrame::global), number(command),
                     {static_cast<double>(ring.size()), 0, 0, 0, g.lat_deg, g.lon_deg, 0});
  };
  for (const auto& ring : mission.inclusion_fences)
    polygon(ring, Cmd::nav_fence_polygon_vertex_inclusion);
  for (const auto& ring : mission.exclusion_fences)
    polygon(ring, Cmd::nav_fence_polygon_vertex_exclusion);
  return out;
}

std::string write_wpl_rally(const Mission& mission) {
  std::string out = "QGC WPL 110\n";
  std::size_t index = 0;
  for (const geometry::GeoPoint& g : mission.rally_points)
    append_wpl_row(out, index++, 0, number(MavFrame::global_relative_alt),
                   number(Cmd::nav_rally_point), {0, 0, 0, 0, g.lat_deg, g.lon_deg, 0});
  return out;
}

std::string write_fen(const Mission& mission) {
  std::string out = "# swath: return point, then the inclusion fence (lat lon)\n";
  auto line = [&](const geometry::GeoPoint& g) {
    base::append_fixed_text(out, g.lat_deg, 9);
    out += ' ';
    base::append_fixed_text(out, g.lon_deg, 9);
    out += '\n';
  };
  line(mission.home);
  if (mission.inclusion_fences.empty()) return out;
  const std::vector<geometry::GeoPoint>& fence = mission.inclusion_fences.front();
  for (const geometry::GeoPoint& g : fence) line(g);
  if (!fence.empty()) line(fence.front());
  return out;
}

}  // namespace swath::missions
