// verify(): every file flown and checked, then the drones against each other (issue 45).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <tuple>

#include "checks.hpp"
#include "swath/base/number_text.hpp"
#include "swath/energy/budget.hpp"
#include "swath/missions/fence_storage.hpp"
#include "swath/preflight/verify.hpp"

namespace swath::preflight {
namespace {

using base::fixed_text;
using geometry::Point2;

// A fence, zone or area as the autopilot (and RFC 7946) reads it: each edge straight in longitude
// and latitude, followed in the frame within kEdgeDepartureTolerance_m by points along it (a long
// edge's chord in the frame strays from it by metres: a route could pass inside the chord and
// outside the fence the autopilot tests).
geometry::Ring local_ring(const geometry::LocalFrame& frame,
                          const std::vector<geometry::GeoPoint>& ring) {
  geometry::Ring out;
  for (const geometry::GeoPoint& g : geometry::densify_lonlat_edges(frame, ring))
    out.push_back(frame.to_local(g));
  if (out.size() > 1 && out.front() == out.back()) out.pop_back();
  return out;
}

// A ring zone or fence, measured with the slack its edges' bow leaves (LocalZone::slack_m): the
// plan reads a zone's edges, in its own frame, within as much of the edge as drawn.
LocalZone ring_zone(std::string name, const geometry::LocalFrame& frame,
                    const std::vector<geometry::GeoPoint>& ring, bool own_fence) {
  const double slack_m = std::min(geometry::kZoneEdgeDepartureTolerance_m,
                                  geometry::largest_lonlat_departure_m(frame, ring));
  return {std::move(name), local_ring(frame, ring), 0, own_fence, slack_m};
}

// A fence or zone with an edge across the ±180° meridian as its longitudes are written
// (geometry::edge_across_antimeridian): ArduPilot and PX4 compare fences in raw longitude, where
// its edge runs the long way round and the shape is the rest of the globe's band, not the one
// drawn; the frame would measure the shape drawn and pass it. Said as a violation of `check`; the
// ring is then left out of the frame's checks, which would measure a shape nobody flies against.
bool across_antimeridian(const std::string& check, const std::string& name,
                         const std::vector<geometry::GeoPoint>& ring, Checked& out) {
  const auto edge = geometry::edge_across_antimeridian(ring);
  if (!edge) return false;
  const auto at = [](const geometry::GeoPoint& g) {
    return fixed_text(g.lat_deg, 7) + ", " + fixed_text(g.lon_deg, 7);
  };
  out.violations.push_back(
      {check, name, edge->a, std::abs(edge->b.lon_deg - edge->a.lon_deg),
       name + " crosses the ±180° meridian (its edge from " + at(edge->a) + " to " + at(edge->b) +
           ", lat, lon): ArduPilot and PX4 compare fences in raw longitude, where that edge runs "
           "the long way round the globe and the fence is not the shape drawn"});
  return true;
}

std::vector<LocalZone> user_zones(const CheckOptions& options, const geometry::LocalFrame& frame,
                                  Checked& out) {
  std::vector<LocalZone> zones;
  for (const Zone& z : options.zones)
    if (!across_antimeridian("no-fly zone", z.name, z.ring, out))
      zones.push_back(ring_zone(z.name, frame, z.ring, false));
  return zones;
}

std::vector<LocalZone> own_exclusions(const missions::Mission& m, const geometry::LocalFrame& frame,
                                      Checked& checked) {
  std::vector<LocalZone> out;
  for (std::size_t i = 0; i < m.exclusion_fences.size(); ++i) {
    const std::string name = m.source + "'s exclusion fence " + std::to_string(i + 1);
    if (!across_antimeridian("no-fly zone", name, m.exclusion_fences[i], checked))
      out.push_back(ring_zone(name, frame, m.exclusion_fences[i], true));
  }
  for (std::size_t i = 0; i < m.exclusion_circles.size(); ++i)
    out.push_back({m.source + "'s exclusion circle " + std::to_string(i + 1),
                   {frame.to_local(m.exclusion_circles[i].centre)},
                   m.exclusion_circles[i].radius_m,
                   true,
                   0.0});
  return out;
}

// Named as the violations say them: "the inclusion fence" when there is one, else which one
// (numbered in the file's order, polygons and circles each from 1).
std::vector<LocalZone> inclusions(const missions::Mission& m, const geometry::LocalFrame& frame,
                                  Checked& checked) {
  std::vector<LocalZone> out;
  const auto rings = missions::distinct_rings(m.inclusion_fences);
  const bool one = rings.size() + m.inclusion_circles.size() == 1;
  auto name = [&](const char* kind, std::size_t i) {
    return one ? std::string("the inclusion fence")
               : m.source + "'s inclusion " + kind + " " + std::to_string(i + 1);
  };
  for (std::size_t i = 0; i < rings.size(); ++i) {
    const std::string fence = name("fence", i);
    // Said as the file's: "the inclusion fence" alone names no file.
    const std::string said = one ? m.source + "'s inclusion fence" : fence;
    if (across_antimeridian("fence", said, rings[i], checked))
      checked.fence_across_antimeridian = true;
    else
      out.push_back(ring_zone(fence, frame, rings[i], false));
  }
  for (std::size_t i = 0; i < m.inclusion_circles.size(); ++i)
    out.push_back({name("circle", i),
                   {frame.to_local(m.inclusion_circles[i].centre)},
                   m.inclusion_circles[i].radius_m,
                   false,
                   0.0});
  return out;
}

// ArduPilot refuses a fence larger than its storage, PX4 one of more than 64 items: said, not
// failed (the mission itself may be flown, with a fence that fits or none, as the pilot decides).
void warn_about_fence_storage(const missions::Mission& m, Report& report) {
  const missions::FenceStorage storage = missions::ardupilot_fence_storage(m);
  std::string warning;
  if (m.autopilot == missions::Autopilot::ardupilot)
    warning = missions::fence_storage_warning(storage, m.fixed_wing);
  if (m.autopilot == missions::Autopilot::px4) warning = missions::px4_fence_warning(storage);
  if (!warning.empty()) report.warnings.push_back(m.source + ": " + warning);
}

// A file's home altitude further than this from the DEM's ground at home is said: its AMSL
// altitudes are measured against the DEM, which the pilot may not have meant (GPS and DEM
// heights agree within a few metres; QGC files often carry 0).
constexpr double kHomeAltitudeSlackM = 5.0;

void warn_about_home_altitude(const missions::Mission& m, const geometry::Ground* ground,
                              Report& report) {
  const bool any_amsl = std::any_of(m.items.begin(), m.items.end(), [](const missions::Item& i) {
    return i.altitude_frame == missions::AltitudeFrame::amsl;
  });
  if (ground == nullptr || !any_amsl || !m.home_amsl_known) return;
  const double dem_m = ground->heights_m({m.home}).at(0);
  if (!std::isfinite(dem_m) || std::abs(m.home_amsl_m - dem_m) <= kHomeAltitudeSlackM) return;
  report.warnings.push_back(m.source + ": the home altitude " + fixed_text(m.home_amsl_m, 1) +
                            " m differs from the DEM's ground at home, " + fixed_text(dem_m, 1) +
                            " m; the altitudes above sea level are checked against the DEM");
}

// The least distance between two points moving linearly over [0, span]: relative position
// r0 + v t, least |r| where the derivative of |r|^2 vanishes, clamped to the interval.
std::pair<double, double> closest_approach(Point3 r0, Point3 v, double span_s) {
  const double vv = v.x * v.x + v.y * v.y + v.z_m * v.z_m;
  const double t =
      vv > 0 ? std::clamp(-(r0.x * v.x + r0.y * v.y + r0.z_m * v.z_m) / vv, 0.0, span_s) : 0.0;
  return {std::hypot(r0.x + v.x * t, r0.y + v.y * t, r0.z_m + v.z_m * t), t};
}

Point3 minus(Point3 a, Point3 b) {
  return {a.x - b.x, a.y - b.y, a.z_m - b.z_m};
}

struct Approach {
  double distance_m = std::numeric_limits<double>::infinity();
  double t_s = 0.0;
};

// Two drones over the time both are airborne, from the later launch to the earlier landing. A
// drone on the ground (before its launch, after it lands) is not checked: one home in the files
// stands for the pads the pilot sets the drones down on, a few metres apart, and a drone waiting
// there is the pilot's to place; the climb and descent through another drone's height are in the
// air and checked. Between consecutive leg ends of either, both move linearly: the least
// distance there is closed-form, so the minimum is exact for the model.
Approach least_separation(const FlownPath& a, double a_launch_s, const FlownPath& b,
                          double b_launch_s) {
  const double a_end = a_launch_s + a.duration_s, b_end = b_launch_s + b.duration_s;
  const double from = std::max(a_launch_s, b_launch_s), to = std::min(a_end, b_end);
  Approach best;
  if (to < from) return best;
  std::vector<double> times{from, to};
  for (const Leg& l : a.legs) times.push_back(a_launch_s + l.t_end_s);
  for (const Leg& l : b.legs) times.push_back(b_launch_s + l.t_end_s);
  std::sort(times.begin(), times.end());
  for (std::size_t i = 0; i + 1 < times.size(); ++i) {
    const double t0 = std::max(times[i], from), t1 = std::min(times[i + 1], to);
    if (t1 < t0) continue;
    const Point3 r0 = minus(position_at(a, t0 - a_launch_s), position_at(b, t0 - b_launch_s));
    const Point3 r1 = minus(position_at(a, t1 - a_launch_s), position_at(b, t1 - b_launch_s));
    const double span = t1 - t0;
    const Point3 v =
        span > 0 ? Point3{(r1.x - r0.x) / span, (r1.y - r0.y) / span, (r1.z_m - r0.z_m) / span}
                 : Point3{};
    const auto [d, t] = closest_approach(r0, v, span);
    if (d < best.distance_m) best = {d, t0 + t};
  }
  return best;
}

// The drone that flies a file (DroneFile::drone).
const std::string& drone_of(const DroneFile& d) {
  if (!d.drone.empty()) return d.drone;
  return d.sorties_of.empty() ? d.mission.source : d.sorties_of;
}

void check_separation(const std::vector<DroneFile>& drones, const std::vector<FlownPath>& paths,
                      const geometry::LocalFrame& frame, const CheckOptions& options,
                      Report& report) {
  const auto flying =
      std::count_if(drones.begin(), drones.end(), [](const DroneFile& d) { return !d.instead; });
  if (flying < 2) {
    report.figures.push_back({"separation", false, {}, "one drone: nothing to keep apart"});
    return;
  }
  Approach least;
  for (std::size_t i = 0; i < paths.size(); ++i)
    for (std::size_t j = i + 1; j < paths.size(); ++j) {
      // One drone flies its sorties in turn, and either its .plan or a twin of it; a twin is
      // checked against the other drones' files (theirs or their twins) at its own times.
      if (drone_of(drones[i]) == drone_of(drones[j])) continue;
      const Approach a = least_separation(paths[i], drones[i].launch_offset_s, paths[j],
                                          drones[j].launch_offset_s);
      least.distance_m = std::min(least.distance_m, a.distance_m);
      if (a.distance_m >= options.separation_m - 1e-3) continue;
      const Point3 p = position_at(paths[i], a.t_s - drones[i].launch_offset_s);
      report.violations.push_back(
          {"separation", paths[i].source, frame.to_geo(p.xy()), options.separation_m - a.distance_m,
           paths[i].source + " and " + paths[j].source + " come within " +
               fixed_text(a.distance_m, 2) + " m of each other at t = " + fixed_text(a.t_s, 1) +
               " s (" + fixed_text(p.z_m, 1) + " m up; " + fixed_text(options.separation_m, 1) +
               " m asked)"});
    }
  report.figures.push_back({"separation", true, least.distance_m,
                            std::isfinite(least.distance_m)
                                ? "least " + fixed_text(least.distance_m, 2) +
                                      " m between two drones at the same time (" +
                                      fixed_text(options.separation_m, 1) + " m asked)"
                                : "the drones are never airborne at the same time"});
}

// The budget's flight is the flown path's (jumps unrolled, circles, holds, the return as RTL flies
// it): each leg's end a point in the drone's own frame, each hold hovered where it is held (one
// before any leg: at the first point).
energy::WaypointMission energy_mission(const DroneFile& d, const FlownPath& path,
                                       const geometry::LocalFrame& frame) {
  energy::WaypointMission m;
  m.drone = std::filesystem::path(d.mission.source).stem().string();
  m.home = d.mission.home;
  m.returns_home = false;
  const geometry::LocalFrame own(m.home);
  double early_hold_s = 0.0;
  for (const Leg& l : path.legs) {
    if (l.kind == LegKind::hold) {
      (m.holds_s.empty() ? early_hold_s : m.holds_s.back()) += l.t_end_s - l.t_start_s;
      continue;
    }
    m.points.push_back(own.to_local(frame.to_geo(l.to.xy())));
    m.altitudes_m.push_back(l.to.z_m);
    m.speeds_m_s.push_back(l.speed_m_s);
    m.holds_s.push_back(m.holds_s.empty() ? early_hold_s : 0.0);
  }
  return m;
}

void check_energy(const DroneFile& d, const FlownPath& path, const geometry::LocalFrame& frame,
                  const CheckOptions& options, Report& report) {
  const energy::DroneBudget b = energy::budget(energy_mission(d, path, frame), *options.drone);
  const std::string figure = d.mission.source + ": " + fixed_text(b.flight_time_s / 60, 1) +
                             " min, lands at " + fixed_text(b.landing_soc * 100, 1) +
                             " % charge (reserve " +
                             fixed_text(options.drone->battery.reserve_soc * 100, 1) + " %)";
  report.figures.push_back({"energy", true, b.flight_time_s, figure});
  if (b.can_finish()) return;
  const energy::BudgetPoint& at = *b.reserve_crossed;
  report.violations.push_back(
      {"energy", d.mission.source, at.geo, -b.reserve_margin,
       d.mission.source + " reaches the " +
           fixed_text(options.drone->battery.reserve_soc * 100, 1) + " % reserve at t = " +
           fixed_text(at.t_s, 0) + " s of " + fixed_text(b.flight_time_s, 0) +
           " s and would land at " + fixed_text(b.landing_soc * 100, 1) + " % (" +
           fixed_text(-b.reserve_margin * 100, 1) + " % into the reserve)"});
}

// Which fences the fence figure is about: the one, or, of several, those the vehicle must stay
// inside (every one; one with --fence-union) or the ones it leaves.
std::string fences_held(const Checked& c, const CheckOptions& o) {
  if (c.most_inclusion_fences <= 1) return " the inclusion fence";
  const std::string n = std::to_string(c.most_inclusion_fences) + " inclusion fences";
  const bool inside = c.least_fence_margin_m >= 0;
  if (o.fence_union)
    return (inside ? " one of the " : " all ") + n + " (ArduPilot files: --fence-union)";
  return (inside ? " every one of the " : " one of the ") + n;
}

void add_figures(const Checked& c, const CheckOptions& o, bool any_zone, Report& report) {
  if (any_zone)
    report.figures.push_back({"zones", true, c.least_clearance_m,
                              "least clearance " + fixed_text(c.least_clearance_m, 2) +
                                  " m, from " + c.least_clearance_where + " (" +
                                  fixed_text(o.clearance_m, 1) + " m asked)"});
  else
    report.figures.push_back({"zones", false, {}, "no zone given and no exclusion fence"});
  if (c.fence_checked)
    report.figures.push_back(
        {"fence", true, c.least_fence_margin_m,
         (c.least_fence_margin_m >= 0
              ? "least margin " + fixed_text(c.least_fence_margin_m, 2) + " m inside"
              : "reaches " + fixed_text(-c.least_fence_margin_m, 2) + " m outside") +
             fences_held(c, o) + " (home, rally points, every leg and stopping margin)"});
  else
    report.figures.push_back(
        {"fence",
         false,
         {},
         c.fence_across_antimeridian
             ? "an inclusion fence crosses the ±180° meridian (violation below)"
             : "no inclusion fence in the files"});
  report.figures.push_back({"ceiling", true, c.max_height_m,
                            "highest " + fixed_text(c.max_height_m, 1) + " m above " +
                                (o.ground ? "the ground" : "home") + " (ceiling " +
                                fixed_text(o.ceiling_m, 1) + " m)"});
  if (o.ground)
    report.figures.push_back({"ground", true, c.min_height_m,
                              "lowest " + fixed_text(c.min_height_m, 1) +
                                  " m above the ground on cruise and return legs (least " +
                                  fixed_text(o.min_height_m, 1) + " m)"});
  else
    report.figures.push_back(
        {"ground", false, {}, "no DEM (--terrain): the ceiling is above home"});
  report.figures.push_back({"photos", true, c.photos,
                            fixed_text(c.photos, 0) + " photos on " + std::to_string(c.photo_legs) +
                                " legs, " + fixed_text(c.transit_photos, 0) + " in transits"});
}

// A flight in place of another's takes the same photos: its transits are checked, its photos
// not counted twice.
void check_photos_instead(const FileContext& f, const std::vector<geometry::Ring>& area,
                          Checked& checked) {
  Checked own;
  check_photos(f, area, own);
  for (Violation& v : own.violations) checked.violations.push_back(std::move(v));
}

// One violation per check and place (a leg's pieces, a waypoint's two legs): the worst.
std::vector<Violation> worst_per_place(std::vector<Violation> all) {
  std::vector<Violation> out;
  for (Violation& v : all) {
    auto same = std::find_if(out.begin(), out.end(), [&](const Violation& o) {
      return o.check == v.check && o.place == v.place;
    });
    if (same == out.end())
      out.push_back(std::move(v));
    else if (v.amount > same->amount)
      *same = std::move(v);
  }
  return out;
}

// Each sortie after the first of its drone launches at its own launch offset or when the one
// before it has landed, whichever is later (one drone flies one sortie at a time). The one before
// is the one launched before it, or of the same offset the one numbered before it, not the one
// listed before it: a directory lists drone-1-10.plan before drone-1-2.plan. Files of one offset
// and number (a split Litchi flight's parts) keep their order.
std::vector<DroneFile> sorties_in_turn(std::vector<DroneFile> drones,
                                       const std::vector<FlownPath>& paths) {
  std::vector<std::size_t> order(drones.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::tie(drones[a].launch_offset_s, drones[a].sortie) <
           std::tie(drones[b].launch_offset_s, drones[b].sortie);
  });
  std::map<std::string, std::size_t> last_of;  // each drone's sortie launched last so far
  for (const std::size_t i : order) {
    if (drones[i].sorties_of.empty()) continue;
    const auto [before, first] = last_of.try_emplace(drones[i].sorties_of, i);
    if (first) continue;
    const std::size_t k = before->second;
    drones[i].launch_offset_s =
        std::max(drones[i].launch_offset_s, drones[k].launch_offset_s + paths[k].duration_s);
    before->second = i;
  }
  return drones;
}

}  // namespace

Report verify(const std::vector<DroneFile>& drones, const CheckOptions& options) {
  Report report;
  if (drones.empty()) return report;
  const geometry::LocalFrame frame(drones.front().mission.home);
  Checked checked;
  const std::vector<LocalZone> zones = user_zones(options, frame, checked);
  std::vector<geometry::Ring> area;
  for (const auto& ring : options.area) area.push_back(local_ring(frame, ring));
  std::vector<FlownPath> paths;
  bool any_zone = !zones.empty();
  for (const DroneFile& d : drones) {
    report.files.push_back(d.mission.source);
    paths.push_back(fly(d.mission, frame, options.model, options.ground.get()));
    FileContext f{d.mission.source, &paths.back(), &frame, {}, 0.0};
    for (const auto& r : d.mission.rally_points) f.rally_points.push_back(frame.to_local(r));
    if (options.ground) f.home_ground_amsl_m = options.ground->heights_m({d.mission.home}).at(0);
    std::vector<LocalZone> all = zones;
    for (LocalZone& z : own_exclusions(d.mission, frame, checked)) all.push_back(std::move(z));
    any_zone = any_zone || all.size() > zones.size();
    check_zones(f, all, options.clearance_m, checked);
    // FENCE_OPTIONS' union is ArduPilot's; PX4 always requires every inclusion fence.
    const bool any_one =
        options.fence_union && d.mission.autopilot == missions::Autopilot::ardupilot;
    check_fences(f, inclusions(d.mission, frame, checked), any_one, checked);
    // A flight in another's place carries that file's fences: said once, of that file.
    if (!d.instead) warn_about_fence_storage(d.mission, report);
    warn_about_home_altitude(d.mission, options.ground.get(), report);
    check_heights(f, options, checked);
    if (d.instead)
      check_photos_instead(f, area, checked);
    else
      check_photos(f, area, checked);
  }
  add_figures(checked, options, any_zone, report);
  report.violations = worst_per_place(std::move(checked.violations));
  if (options.drone)
    for (std::size_t i = 0; i < drones.size(); ++i)
      check_energy(drones[i], paths[i], frame, options, report);
  else
    report.figures.push_back({"energy", false, {}, "no drone profile (--drone)"});
  const std::vector<DroneFile> launched = sorties_in_turn(drones, paths);
  check_separation(launched, paths, frame, options, report);
  std::string times;
  for (std::size_t i = 0; i < paths.size(); ++i)
    times += (i ? ", " : "") + paths[i].source + " " + fixed_text(paths[i].duration_s / 60, 1) +
             " min from t = " + fixed_text(launched[i].launch_offset_s, 0) + " s";
  report.figures.push_back({"flight", true, {}, "as the autopilot flies it: " + times});
  return report;
}

}  // namespace swath::preflight
