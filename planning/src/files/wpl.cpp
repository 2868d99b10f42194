// QGC WPL 110 files (Mission Planner): missions, and ArduPilot polygon fences and rally points.
#include "common.hpp"
#include "swath/base/number_text.hpp"

namespace swath::planning {

using mavlink::Cmd;

std::string wpl_110(const SurveyPlan& plan, const Flight& flight) {
  const geometry::GeoPoint home = files::rounded(flight.drone->home_geo);
  std::string out = "QGC WPL 110\n";
  // Row 0 is the home, above mean sea level (0 when swath does not know the ground there).
  out += files::wpl_row(
      0, 1, files::kFrameGlobal, files::cmd(Cmd::nav_waypoint),
      {0, 0, 0, 0, home.lat_deg, home.lon_deg, base::round_to(flight.mission->home_amsl_m, 3)});
  std::size_t index = 1;
  for (const MissionItem& item : flight.mission->items)
    out += files::wpl_row(index++, 0, files::mav_frame(plan, item),
                          files::mav_command(item, plan.request.firmware),
                          files::mav_params(plan, item));
  return out;
}

std::string fence_waypoints(const SurveyPlan& plan) {
  // MAV_CMD_NAV_FENCE_POLYGON_VERTEX_INCLUSION / _EXCLUSION: param1 is the polygon's vertex count,
  // repeated on each of its vertices.
  std::string out = "QGC WPL 110\n";
  std::size_t index = 0;
  auto polygon = [&](const std::vector<geometry::GeoPoint>& ring, int command) {
    for (const geometry::GeoPoint& g : ring)
      out += files::wpl_row(index++, 0, files::kFrameGlobal, command,
                            {static_cast<double>(ring.size()), 0, 0, 0, g.lat_deg, g.lon_deg, 0});
  };
  for (const geometry::Ring& ring : plan.fence) {
    std::vector<geometry::GeoPoint> geo;
    for (const geometry::Point2& p : ring) geo.push_back(files::geo(plan, p));
    polygon(geo, files::cmd(Cmd::nav_fence_polygon_vertex_inclusion));
  }
  for (const auto& zone : plan.exclusion_fences_geo) {
    std::vector<geometry::GeoPoint> geo;
    for (const geometry::GeoPoint& g : zone) geo.push_back(files::rounded(g));
    polygon(geo, files::cmd(Cmd::nav_fence_polygon_vertex_exclusion));
  }
  return out;
}

std::string fence_fen(const SurveyPlan& plan) {
  // The legacy fence list Mission Planner reads: the return point, then the polygon, closed.
  std::string out = "# swath: return point, then the inclusion fence (lat lon)\n";
  auto line = [&](const geometry::GeoPoint& g) {
    out += base::fixed_text(g.lat_deg, 9) + " " + base::fixed_text(g.lon_deg, 9) + "\n";
  };
  line(files::rounded(plan.home));
  if (plan.fence.empty()) return out;
  for (const geometry::Point2& p : plan.fence.front()) line(files::geo(plan, p));
  line(files::geo(plan, plan.fence.front().front()));
  return out;
}

std::string rally_waypoints(const SurveyPlan& plan) {
  std::string out = "QGC WPL 110\n";
  std::size_t index = 0;
  for (const DronePlan& d : plan.drones) {
    const geometry::GeoPoint g = files::rounded(d.home_geo);
    out += files::wpl_row(index++, 0, files::kFrameRelativeAlt, files::cmd(Cmd::nav_rally_point),
                          {0, 0, 0, 0, g.lat_deg, g.lon_deg, 0});
  }
  return out;
}

}  // namespace swath::planning
