// Missions that fly as planned (docs/swath-plan.md), checked from the written files with geometry
// of the test's own (closed-form segment distances, ray casting): every waypoint and leg keeps the
// clearance from the no-fly zones the .plan fences; the fences are the area and the zones; photos
// lie on the lines; sorties fit the battery and together fly the whole survey; fixed-wing turns are
// at least two turn radii wide; and a point-mass multirotor flies each .plan item by item as
// ArduCopter does (seq 0 = home, speed and acceleration limits, 2 m waypoint radius, stops at sharp
// corners, distance trigger), keeping the clearance and taking swath's estimated time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "meadow_survey.hpp"
#include "plan_reader.hpp"
#include "random_polygons.hpp"
#include "swath/base/input_error.hpp"
#include "swath/geometry/field.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/planning/survey_files.hpp"

namespace swath::planning {
namespace {

using geometry::GeoPoint;
using geometry::Point2;
using geometry::Polygon;
using geometry::Ring;
using nlohmann::json;
using vehicle::Drone;
using vehicle::Fleet;
using vehicle::parse_fleet;

using namespace plan_reader;  // NOLINT: the reader is the test's vocabulary

// ---- A point-mass multirotor flying the items as ArduCopter does -------------------------------

// ArduCopter's defaults (WPNAV_SPEED 10 m/s until a DO_CHANGE_SPEED, WPNAV_ACCEL 2.5 m/s²,
// WPNAV_SPEED_UP 2.5 m/s, WPNAV_SPEED_DN 1.5 m/s, WPNAV_RADIUS 2 m). A waypoint is passed within
// the radius unless the drone must stop there (a hold, a corner sharper than 45°, the last one;
// reached within 0.2 m below 0.5 m/s);
// the velocity follows the command with a 0.15 s lag and the acceleration limit, so corners are
// cut and stops overshoot as a real vehicle's do. The camera's distance trigger takes a photo where
// it is started and then whenever the drone is the trigger distance from the last photo.
struct Flown {
  std::vector<Point2> track;  // every 10 ms
  std::vector<Point2> photos;
  double time_s = 0.0;  // take-off to touch-down
};

class PointMass {
 public:
  explicit PointMass(Point2 home) : p_(home), from_(home) { out_.track.push_back(home); }

  Flown fly(const ReadPlan& plan) {
    std::vector<std::size_t> nav;
    for (std::size_t i = 0; i < plan.items.size(); ++i)
      if (positional(plan.items[i].command) || plan.items[i].command == 20) nav.push_back(i);
    for (std::size_t i = 0; i < plan.items.size(); ++i) {
      const PlanItem& it = plan.items[i];
      switch (it.command) {
        case 22:
          vertical(it.altitude_m, 2.5);
          break;
        case 178:
          speed_ = it.params.at(1);
          break;
        case 206:
          trigger(it.params.at(0));
          break;
        case 16: {
          const auto k = std::find(nav.begin(), nav.end(), i) - nav.begin();
          const Point2 next =
              k + 1 < static_cast<long>(nav.size())
                  ? (plan.items[nav[k + 1]].command == 20 ? plan.home
                                                          : plan.items[nav[k + 1]].position)
                  : it.position;
          const double hold = std::isnan(it.params.at(0)) ? 0.0 : it.params.at(0);
          horizontal(it.position, hold > 0 ? 0.0 : corner_speed(it.position, next), speed_, next);
          wait(hold);
          break;
        }
        case 20:  // RTL: home at RTL_SPEED 0 = WPNAV_SPEED (the mission's speed override ends)
          horizontal(plan.home, 0.0, rtl_speed_m_s, plan.home);
          vertical(0, 1.5);
          break;
        case 21:
          horizontal(it.position, 0.0, speed_, it.position);
          vertical(0, 1.5);
          break;
        default:
          break;
      }
    }
    return out_;
  }

  double rtl_speed_m_s = 10.0;

 private:
  // The speed a corner is flown through: 0 (a stop) when sharper than 45°, otherwise what keeps
  // the sideways acceleration within half the limit on the arc that fits the waypoint radius
  // (ArduCopter's corners are jerk-limited S-curves within its acceleration limit).
  double corner_speed(Point2 at, Point2 next) const {
    const Point2 in = at - from_, out = next - at;
    if (norm(in) < 1e-6 || norm(out) < 1e-6) return 0.0;
    const double c = std::clamp((in.x * out.x + in.y * out.y) / (norm(in) * norm(out)), -1.0, 1.0);
    const double turn = std::acos(c);
    if (turn >= 45.0 * M_PI / 180.0 - 1e-9) return 0.0;
    if (turn < 1e-6) return INFINITY;
    return std::sqrt(0.5 * kAccel * kRadius_m / std::tan(turn / 2));
  }

  void step(Point2 v_cmd) {
    Point2 a = (v_cmd - v_) * (1.0 / kLag_s);
    if (norm(a) > kAccel) a = a * (kAccel / norm(a));
    v_ = v_ + a * kDt;
    p_ = p_ + v_ * kDt;
    out_.time_s += kDt;
    out_.track.push_back(p_);
    if (trigger_m_ > 0 && norm(p_ - out_.photos.back()) >= trigger_m_) out_.photos.push_back(p_);
  }

  // Along the leg from the last waypoint to `target` as ArduCopter's position controller does:
  // the drone chases a target point a little ahead of it on the path (past a corner it flies
  // through, onto the next leg: corners are cut on their inside, as the S-curve blends do), at
  // the speed that brakes to the corner speed (0: a stop) at the acceleration limit. Passed
  // within the waypoint radius; a stop is reached within 0.2 m below 0.5 m/s.
  void horizontal(Point2 target, double corner_m_s, double speed, Point2 next) {
    const bool stop = corner_m_s == 0.0;
    const Point2 leg = target - from_;
    const double leg_m = norm(leg);
    const Point2 out = next - target;
    const Point2 u_next = norm(out) > 1e-9 ? out * (1.0 / norm(out)) : Point2{};
    for (int guard = 0; guard < 10'000'000; ++guard) {
      const Point2 d = target - p_;
      const double dist = norm(d);
      const Point2 u = leg_m > 0.5 ? leg * (1.0 / leg_m) : d * (1.0 / std::max(dist, 1e-9));
      const double along = d.x * u.x + d.y * u.y;
      if (stop ? dist < 0.2 && norm(v_) < 0.5 : (dist < kRadius_m || along < 0)) break;
      // Braking to the corner speed where the corner begins (the point itself for a stop, the
      // waypoint radius before it otherwise), on the distance left once the velocity lag is flown
      // (a lead, as a position controller's feed-forward does).
      const double v_along = v_.x * u.x + v_.y * u.y;
      const double left =
          std::abs(along) - (stop ? 0.0 : kRadius_m) - std::max(v_along, 0.0) * kLag_s;
      const double v =
          std::min(speed, std::sqrt(corner_m_s * corner_m_s + 2 * kAccel * std::max(left, 0.0)));
      const double ahead_m = std::max(1.0, norm(v_) * 0.5);
      Point2 carrot = target;
      if (leg_m > 0.5 && along > ahead_m)
        carrot = target - u * (along - ahead_m);
      else if (!stop)
        carrot = target + u_next * (ahead_m - std::max(along, 0.0));
      const Point2 to = carrot - p_;
      step(norm(to) > 1e-9 ? to * (v / norm(to)) : Point2{});
    }
    from_ = target;
  }

  void vertical(double altitude_m, double rate_m_s) {  // trapezoid at the climb/descent rate
    const double h = std::abs(altitude_m - z_);
    const double ramp = rate_m_s / kAccel;
    out_.time_s += h >= rate_m_s * ramp ? h / rate_m_s + ramp : 2 * std::sqrt(h / kAccel);
    z_ = altitude_m;
  }

  void wait(double s) {  // hovering in place
    if (s > 0) v_ = {};
    out_.time_s += s;
  }

  void trigger(double distance_m) {
    trigger_m_ = distance_m;
    if (distance_m > 0) out_.photos.push_back(p_);
  }

  static constexpr double kDt = 0.01, kAccel = 2.5, kLag_s = 0.15, kRadius_m = 2.0;
  Point2 p_, v_, from_;
  double z_ = 0.0, speed_ = 10.0, trigger_m_ = 0.0;
  Flown out_;
};

// ---- Plans -------------------------------------------------------------------------------------

using test::local_field;

Ring circle(Point2 c, double r, int n) {
  Ring ring;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n + 0.3;
    ring.push_back({c.x + r * std::cos(a), c.y + r * 0.8 * std::sin(a)});
  }
  return ring;
}

// A 520 m x 320 m field with a pond and a barn, home south-west of it (the pair of drones
// flew 17-76 m legs straight through these).
SurveyRequest pond_and_barn(int drones, DivisionMode division) {
  Polygon p;
  p.outer = {{0, 0}, {520, 0}, {520, 200}, {400, 320}, {0, 320}};
  p.holes = {circle({170, 150}, 45, 9), {{330, 70}, {370, 70}, {370, 95}, {330, 95}}};
  SurveyRequest r;
  r.field = local_field(p);
  r.camera = {"test", 23.2, 15.4, 16, 5456, 3632, std::nullopt};
  PhotogrammetryMode m;
  m.altitude_m = 40;  // footprint 58 m, spacing 17.4 m at 70 % side overlap
  m.side_overlap = 0.7;
  r.mode = m;
  const geometry::LocalFrame& frame = *r.field.frame;
  r.home = frame.to_geo({-60, -40});
  if (drones > 1) {
    Fleet fleet;
    fleet.home = *r.home;
    for (int i = 0; i < drones; ++i) {
      Drone d;
      d.name = i == 0 ? "alpha" : "bravo";
      d.battery_level = 1.0;
      d.endurance_s = 1800;
      d.speed_m_s = i == 0 ? 5.0 : 7.0;
      if (i == 1) d.home = frame.to_geo({600, 360});  // its own launch point north-east
      fleet.drones.push_back(d);
    }
    r.fleet = fleet;
    r.division = division;
  }
  return r;
}

SurveyRequest vineyard(bool pair) {
  SurveyRequest r = test::vineyard_request();
  if (pair)
    r.fleet = parse_fleet(
        "home: {lat: 46.2276, lon: 7.5917}\n"
        "drones:\n"
        "  - {name: alpha, battery_level: 1.0, endurance_s: 1500, speed_m_s: 5}\n"
        "  - {name: bravo, battery_level: 0.8, endurance_s: 1500, speed_m_s: 6}\n",
        "vineyard-pair");
  return r;
}

// The zones a plan must keep away from, as the user gave them: the field's holes and --exclude.
std::vector<Ring> given_zones(const SurveyRequest& r) {
  std::vector<Ring> zones = r.field.polygon.holes;
  for (const auto& z : r.exclusions) {
    Ring ring;
    for (const GeoPoint& g : z) ring.push_back(r.field.frame->to_local(g));
    zones.push_back(ring);
  }
  return zones;
}

// Whether two rings have the same vertices (any start, any direction, closing vertex or not).
bool same_ring(Ring a, Ring b, double tol_m) {
  auto open = [](Ring& r) {
    if (r.size() > 1 && norm(r.front() - r.back()) < 1e-9) r.pop_back();
  };
  open(a);
  open(b);
  if (a.size() != b.size()) return false;
  for (const Point2& p : a)
    if (std::none_of(b.begin(), b.end(), [&](Point2 q) { return norm(p - q) <= tol_m; }))
      return false;
  return true;
}

double summary_flight_time_s(const SurveyPlan& plan, const std::string& stem) {
  const json s = json::parse(summary_json(plan));
  for (const json& d : s.at("drones")) {
    if (d.at("file") == stem) return d.at("flight_time_s").get<double>();
    for (const json& so : d.at("sorties"))
      if (so.at("file") == stem) return so.at("flight_time_s").get<double>();
  }
  ADD_FAILURE() << "no flight " << stem << " in summary.json";
  return NAN;
}

// Everything docs/swath-plan.md, 'Missions that fly as planned' promises of one plan, read back
// from its files.
void check_flights(const SurveyPlan& plan, const std::string& what) {
  SCOPED_TRACE(what);
  const geometry::LocalFrame& frame = *plan.request.field.frame;
  const std::vector<Ring> zones = given_zones(plan.request);
  const double clearance = plan.request.clearance_m;
  for (const Flight& f : flights_of(plan)) {
    SCOPED_TRACE(f.file_stem);
    const ReadPlan p = read_plan(qgc_plan(plan, f), frame);
    // The drone's own home and speed.
    EXPECT_LT(norm(p.home - f.drone->home), 0.01);
    ASSERT_GE(p.items.size(), 3u);
    EXPECT_EQ(p.items[0].command, 22);
    EXPECT_EQ(p.items[1].command, 178);
    EXPECT_DOUBLE_EQ(p.items[1].params.at(1), f.drone->speed_m_s);
    EXPECT_DOUBLE_EQ(p.cruise_m_s, f.drone->speed_m_s);
    ASSERT_EQ(p.rally.size(), 1u);
    EXPECT_LT(norm(p.rally[0] - f.drone->home), 0.01);

    // Fences: one exclusion per zone, the inclusion the area grown by the margin. A zone is
    // fenced as given, or where it has more vertices than PX4 stores in one polygon, by a polygon
    // of at most that many that holds every vertex of it, lies within half the clearance of it,
    // and that no commanded leg enters.
    ASSERT_EQ(p.exclusions.size(), zones.size());
    for (const Ring& z : zones) {
      if (z.size() <= kFenceVertexLimit) {
        EXPECT_TRUE(std::any_of(p.exclusions.begin(), p.exclusions.end(),
                                [&](const Ring& e) { return same_ring(e, z, 0.01); }));
        continue;
      }
      const auto holding =
          std::find_if(p.exclusions.begin(), p.exclusions.end(), [&](const Ring& e) {
            return e.size() <= kFenceVertexLimit &&
                   std::all_of(z.begin(), z.end(), [&](Point2 v) { return inside(v, e); });
          });
      ASSERT_NE(holding, p.exclusions.end()) << "no fence of at most " << kFenceVertexLimit
                                             << " vertices holds a zone of " << z.size();
      for (const Point2& v : *holding) {
        double to_zone = INFINITY;
        for (std::size_t i = 0; i < z.size(); ++i)
          to_zone = std::min(to_zone, point_segment_m(v, z[i], z[(i + 1) % z.size()]));
        EXPECT_LE(to_zone, clearance / 2 + 0.01);
      }
      EXPECT_GT(least_clearance(commanded_path(p), {*holding}).distance_m, clearance / 2 - 0.01);
    }
    ASSERT_FALSE(p.inclusions.empty());
    const Ring& outer = plan.request.field.polygon.outer;
    for (const Point2& v : outer)
      EXPECT_TRUE(std::any_of(p.inclusions.begin(), p.inclusions.end(),
                              [&](const Ring& in) { return inside(v, in); }));
    double fence_gap = INFINITY;
    for (const Ring& in : p.inclusions) fence_gap = std::min(fence_gap, ring_ring_m(in, outer));
    EXPECT_GE(fence_gap, plan.fence_margin_m - 0.01);
    EXPECT_LE(fence_gap, plan.fence_margin_m + 0.01);

    // Every waypoint and every commanded leg keeps the clearance.
    if (!zones.empty()) {
      const Closest c = least_clearance(commanded_path(p), zones);
      EXPECT_GE(c.distance_m, clearance - 0.01) << c;
    }

    // A stop beside a zone is drawn back along its line: a drone that overshoots it by
    // speed² / (2 x 2.5 m/s²), straight on (ArduCopter SITL: 0.42 m at 5 m/s; the bound of a
    // vehicle that starts braking at the waypoint), still keeps the clearance.
    std::vector<Point2> holds;
    for (const PlanItem& it : p.items)
      if (it.command == 16 && !std::isnan(it.params.at(0)) && it.params.at(0) > 0)
        holds.push_back(it.position);
    std::size_t stops_checked = 0;
    for (const SweepLine& l : f.mission->lines) {
      for (const std::pair<Point2, Point2>& ends :
           {std::pair{l.end, l.start}, std::pair{l.start, l.end}}) {
        const Point2 end = ends.first, from = ends.second;  // a lambda below captures `end`
        const bool held =
            std::any_of(holds.begin(), holds.end(), [&](Point2 h) { return norm(h - end) < 0.01; });
        const double length_m = norm(end - from);
        const double overrun_m = stop_overrun_m(f.drone->speed_m_s);
        if (!held || zones.empty() || length_m < 2 * overrun_m) continue;
        const Point2 past = end + (end - from) * (overrun_m / length_m);
        const Closest c = least_clearance({end, past}, zones);
        EXPECT_GE(c.distance_m, clearance - 0.01) << "overshooting a stop: " << c;
        ++stops_checked;
      }
    }
    if (!zones.empty() && !holds.empty()) {
      EXPECT_GT(stops_checked, 0u);
    }

    // Flown as ArduCopter flies it: the track keeps the clearance less 1 m, the time is swath's.
    PointMass drone(p.home);
    drone.rtl_speed_m_s = f.drone->speed_m_s;
    const Flown flown = drone.fly(p);
    std::vector<Point2> sampled;  // every 50 ms
    for (std::size_t i = 0; i < flown.track.size(); i += 5) sampled.push_back(flown.track[i]);
    sampled.push_back(flown.track.back());
    if (!zones.empty()) {
      const Closest c = least_clearance(sampled, zones);
      EXPECT_GE(c.distance_m, clearance - 1.0) << c;
    }
    const double estimate = summary_flight_time_s(plan, f.file_stem);
    EXPECT_NEAR(flown.time_s, estimate, 0.05 * estimate);

    // Photos on the lines only: the planned ones exactly, the flown trigger's within the track's
    // error; as many as planned within the trigger's rounding.
    auto off_lines = [&](Point2 q) {
      double d = INFINITY;
      for (const SweepLine& l : f.mission->lines)
        d = std::min(d, point_segment_m(q, l.start, l.end));
      return d;
    };
    ASSERT_FALSE(f.photos->empty());
    for (const PhotoPoint& ph : *f.photos) EXPECT_LT(off_lines(ph.position), 0.01);
    for (const Point2& q : flown.photos) EXPECT_LT(off_lines(q), 2.0) << q.x << " " << q.y;
    EXPECT_NEAR(static_cast<double>(flown.photos.size()), static_cast<double>(f.photos->size()),
                0.03 * static_cast<double>(f.photos->size()) + 2);
  }
}

// ---- Tests -------------------------------------------------------------------------------------

TEST(FlightTrue, VineyardKeepsItsClearanceFromThePondAndFliesAsEstimated) {
  const SurveyPlan plan = plan_survey(vineyard(false));
  ASSERT_TRUE(plan.clearance.no_fly_m);
  EXPECT_GE(*plan.clearance.no_fly_m, 5.0 - 1e-6);
  check_flights(plan, "vineyard");
}

TEST(FlightTrue, VineyardPairEachWithItsSpeed) {
  const SurveyPlan plan = plan_survey(vineyard(true));
  ASSERT_EQ(plan.drones.size(), 2u);
  EXPECT_EQ(plan.drones[1].speed_m_s, 6.0);
  check_flights(plan, "vineyard pair");
}

TEST(FlightTrue, TwoDronesAroundAPondAndABarnByPathAndByRegion) {
  for (DivisionMode division : {DivisionMode::path, DivisionMode::region}) {
    const SurveyPlan plan = plan_survey(pond_and_barn(2, division));
    ASSERT_EQ(plan.drones.size(), 2u);
    check_flights(plan, division == DivisionMode::path ? "path" : "region");
  }
}

TEST(FlightTrue, ExcludedZoneIsFencedAndKeptClearOf) {
  SurveyRequest r = test::meadow_request(60);
  const std::vector<Point2> square = {{-40, -40}, {40, -40}, {40, 40}, {-40, 40}};
  // A zone in the middle of the meadow, given in WGS84 as --exclude takes it.
  Point2 mid{};
  for (const Point2& v : r.field.polygon.outer)
    mid = mid + v * (1.0 / static_cast<double>(r.field.polygon.outer.size()));
  std::vector<GeoPoint> zone;
  for (const Point2& v : square) zone.push_back(r.field.frame->to_geo(mid + v));
  r.exclusions = {zone};
  r.clearance_m = 8;
  const SurveyPlan plan = plan_survey(r);
  EXPECT_GE(*plan.clearance.no_fly_m, 8.0 - 1e-6);
  check_flights(plan, "meadow with a zone");
}

// A pond traced with 200 vertices: PX4 stores at most 64 in one exclusion fence, so the .plan's
// fence for it is the pond simplified outward (holding it, within half the clearance of it) and
// no warning is left; the plan keeps the clearance from the pond itself (check_flights). With no
// clearance there is no room to simplify into: the pond as given, and the warning.
TEST(FlightTrue, AZoneOfManyVerticesIsFencedWithinWhatAnAutopilotStores) {
  SurveyRequest r = test::meadow_request(60);
  Point2 mid{};
  for (const Point2& v : r.field.polygon.outer)
    mid = mid + v * (1.0 / static_cast<double>(r.field.polygon.outer.size()));
  std::vector<GeoPoint> pond;
  for (int k = 0; k < 200; ++k) {
    const double a = 2 * 3.14159265358979 * k / 200, radius_m = 35 + 6 * std::sin(5 * a);
    pond.push_back(r.field.frame->to_geo(mid + Point2{std::cos(a), std::sin(a)} * radius_m));
  }
  r.exclusions = {pond};
  r.clearance_m = 8;
  const SurveyPlan plan = plan_survey(r);
  ASSERT_EQ(plan.exclusion_fences_geo.size(), 1u);
  EXPECT_LE(plan.exclusion_fences_geo[0].size(), kFenceVertexLimit);
  EXPECT_GE(plan.exclusion_fences_geo[0].size(), 8u);
  for (const std::string& w : plan.warnings)
    EXPECT_EQ(w.find("no-fly zone"), std::string::npos) << w;
  check_flights(plan, "meadow with a 200-vertex pond");

  r.clearance_m = 0;
  const SurveyPlan tight = plan_survey(r);
  ASSERT_EQ(tight.exclusion_fences_geo.size(), 1u);
  EXPECT_EQ(tight.exclusion_fences_geo[0].size(), 200u);
  EXPECT_TRUE(std::any_of(tight.warnings.begin(), tight.warnings.end(), [](const std::string& w) {
    return w.find("no-fly zone 1 has 200 vertices") != std::string::npos &&
           w.find("more than the 64 PX4 stores") != std::string::npos;
  }));
}

// An outline of 300 (and of 2,000) vertices, as drawn from a detailed survey: grown exactly, its
// fence had ~300 vertices, more than PX4 stores in one polygon (64). The .plan's inclusion fence
// fits, and still holds every point within the margin of the outline: points at 0.999 x the
// margin off every vertex, in 8 directions, read back from the file.
TEST(FlightTrue, ALongOutlinesFenceFitsAnAutopilotAndHoldsTheMargin) {
  test::Rng rng(6464);
  for (const std::size_t n : {std::size_t(300), std::size_t(2000)}) {
    SCOPED_TRACE(n);
    SurveyRequest r;
    r.field = local_field({test::random_field_polygon(rng, n, 250), {}});
    r.camera = {"test", 23.2, 15.4, 16, 5456, 3632, std::nullopt};
    PhotogrammetryMode m;
    m.altitude_m = 60;
    r.mode = m;
    const SurveyPlan plan = plan_survey(r);
    const ReadPlan p =
        read_plan(qgc_plan(plan, flights_of(plan).front()), *plan.request.field.frame);
    ASSERT_FALSE(p.inclusions.empty());
    for (const Ring& in : p.inclusions) EXPECT_LE(in.size(), kFenceVertexLimit);
    const double reach_m = 0.999 * plan.fence_margin_m;
    for (const Point2& v : plan.request.field.polygon.outer)
      for (int k = 0; k < 8; ++k) {
        const Point2 q = v + Point2{std::cos(k * 0.785398), std::sin(k * 0.785398)} * reach_m;
        ASSERT_TRUE(std::any_of(p.inclusions.begin(), p.inclusions.end(),
                                [&](const Ring& in) { return inside(q, in); }))
            << q.x << ", " << q.y;
      }
    // No warning about the fence (these flights are long: the endurance warning may be there).
    for (const std::string& w : plan.warnings) EXPECT_EQ(w.find("fence"), std::string::npos) << w;
  }
}

// A zone across the whole field cuts it in two; a second zone lies inside the smaller part, so
// it is a hole of an extra piece. The area reported is the rectangle less both zones (closed
// form: 400 x 200 - 20 x 200 - 30 x 30 = 75,100 m²; it was 76,000 when the piece's hole was
// dropped) and the coverage is measured without the hole (0.988 when it counted as unseen).
TEST(FlightTrue, ZoneInACutOffPieceIsOutOfTheAreaAndItsCoverage) {
  SurveyRequest r = pond_and_barn(1, DivisionMode::path);
  r.field = local_field({{{0, 0}, {400, 0}, {400, 200}, {0, 200}}, {}});
  const geometry::LocalFrame& frame = *r.field.frame;
  r.home = frame.to_geo({-30, -30});
  auto zone = [&](std::vector<Point2> ring) {
    std::vector<GeoPoint> geo;
    for (const Point2& v : ring) geo.push_back(frame.to_geo(v));
    return geo;
  };
  r.exclusions = {zone({{200, -20}, {220, -20}, {220, 220}, {200, 220}}),
                  zone({{300, 80}, {330, 80}, {330, 110}, {300, 110}})};
  r.clearance_m = 5;
  const SurveyPlan plan = plan_survey(r);
  ASSERT_EQ(plan.extra_pieces.size(), 1u);
  EXPECT_NEAR(*plan.facts.area_m2, 75100.0, 1.0);
  EXPECT_GE(plan.coverage.covered_fraction, 0.999);
  check_flights(plan, "field cut in two by a zone, a zone in the cut-off part");
}

TEST(FlightTrue, HoverAndTimeTriggerModes) {
  for (TriggerMode mode : {TriggerMode::time, TriggerMode::hover}) {
    SurveyRequest r = pond_and_barn(1, DivisionMode::path);
    r.triggering.mode = mode;
    const SurveyPlan plan = plan_survey(r);
    const Flight f = flights_of(plan).at(0);
    const ReadPlan p = read_plan(qgc_plan(plan, f), *r.field.frame);
    int starts = 0, stops = 0, shots = 0;
    for (const PlanItem& it : p.items) {
      starts += it.command == 2000 && it.params.at(2) == 0;
      stops += it.command == 2001;
      shots += (it.command == 2000 && it.params.at(2) == 1) || it.command == 203;
    }
    if (mode == TriggerMode::time) {
      EXPECT_EQ(starts, static_cast<int>(f.mission->lines.size()));
      EXPECT_EQ(stops, starts);
      // The interval is the trigger distance at the drone's speed.
      for (const PlanItem& it : p.items) {
        if (it.command == 2000) {
          EXPECT_NEAR(it.params.at(1), plan.imaging.trigger_distance_m / f.drone->speed_m_s, 1e-3);
        }
      }
    } else {
      EXPECT_EQ(shots, static_cast<int>(f.photos->size()));
      PointMass drone(p.home);
      drone.rtl_speed_m_s = f.drone->speed_m_s;
      const double estimate = summary_flight_time_s(plan, f.file_stem);
      EXPECT_NEAR(drone.fly(p).time_s, estimate, 0.05 * estimate);
    }
  }
}

TEST(FlightTrue, SortiesFitTheBatteryAndTogetherFlyTheWholeSurvey) {
  SurveyRequest r = test::meadow_request(60);
  r.home = GeoPoint{47.3965, 8.5405, 0};
  r.endurance_s = 420;  // the meadow takes ~15 min: three sorties or more
  r.reserve = 0.2;
  r.sorties = true;
  const SurveyPlan plan = plan_survey(r);
  SurveyRequest whole_r = r;  // the uncut flight: no battery (with one it would be refused)
  whole_r.sorties = false;
  whole_r.endurance_s.reset();
  const SurveyPlan whole = plan_survey(whole_r);
  const DronePlan& d = plan.drones.at(0);
  ASSERT_GE(d.sorties.size(), 3u);
  double work = 0;
  std::size_t photos = 0;
  for (const Flight& f : flights_of(plan)) {
    SCOPED_TRACE(f.file_stem);
    EXPECT_EQ(f.file_stem, "drone-1-" + std::to_string(f.sortie));
    EXPECT_LE(f.mission->flight_time_s, 420 * 0.8 + 1e-6);
    const ReadPlan p = read_plan(qgc_plan(plan, f), *r.field.frame);
    const std::vector<Point2> path = commanded_path(p);
    EXPECT_LT(norm(path.front() - d.home), 0.01);  // home -> ... -> home
    EXPECT_LT(norm(path.back() - d.home), 0.01);
    // The sortie as flown also fits: the point mass lands within the usable time (+5 %).
    PointMass drone(p.home);
    drone.rtl_speed_m_s = d.speed_m_s;
    EXPECT_LE(drone.fly(p).time_s, 420 * 0.8 * 1.05);
    work += f.mission->work_length_m;
    photos += f.photos->size();
  }
  // Together: the whole survey's line length (cut exactly) less the stubs outside the area a cut
  // leaves a sortie as transits (a line's end beyond the area: at most the turnaround and half the
  // footprint), and its photos within one per cut.
  const double whole_work = whole.drones[0].mission.work_length_m;
  const double cuts = static_cast<double>(d.sorties.size() - 1);
  EXPECT_LE(work, whole_work + 0.01);
  EXPECT_GE(work,
            whole_work - cuts * (plan.turnaround_m + plan.imaging.footprint_across_m / 2) - 0.01);
  EXPECT_NEAR(static_cast<double>(photos), static_cast<double>(whole.drones[0].photos.size()),
              static_cast<double>(d.sorties.size()));
  // Every point of the whole survey's lines in the area is on some sortie's line.
  for (const SweepLine& l : whole.drones[0].mission.lines)
    for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      const Point2 q = l.start + (l.end - l.start) * t;
      if (geometry::locate_point(q, plan.flown_area.outer) == geometry::Containment::outside)
        continue;
      double best = INFINITY;
      for (const Sortie& s : d.sorties)
        for (const SweepLine& m : s.mission.lines)
          best = std::min(best, point_segment_m(q, m.start, m.end));
      EXPECT_LT(best, 0.01);
    }
}

TEST(FlightTrue, FixedWingTurnsAreAtLeastTwoTurnRadiiWide) {
  SurveyRequest r = test::meadow_request(60);
  r.vehicle = Vehicle::fixedwing;
  r.speed_m_s = 15;
  const SurveyPlan plan = plan_survey(r);
  const double radius = 15.0 * 15.0 / (9.80665 * std::tan(30 * M_PI / 180));
  EXPECT_NEAR(plan.turn_radius_m, radius, 0.05);
  const auto& lines = plan.drones.at(0).mission.lines;
  ASSERT_GE(lines.size(), 4u);
  for (std::size_t i = 0; i + 1 < lines.size(); ++i)
    EXPECT_GE(norm(lines[i + 1].start - lines[i].end), 2 * radius - 0.01) << "turn " << i;
  // Interleaving keeps the coverage of flying them in order.
  SurveyRequest slow = r;
  slow.vehicle = Vehicle::multirotor;
  slow.speed_m_s = 5;
  EXPECT_NEAR(plan.coverage.covered_fraction, plan_survey(slow).coverage.covered_fraction, 1e-9);
}

TEST(FlightTrue, SanityWarningsNameTheLimitAndTheWayOut) {
  SurveyRequest high = test::meadow_request(150);
  const SurveyPlan h = plan_survey(high);
  EXPECT_TRUE(std::any_of(h.warnings.begin(), h.warnings.end(), [](const std::string& w) {
    return w.find("above 120 m") != std::string::npos;
  }));
  // A flight longer than the endurance less the reserve is refused, sorties among the ways out.
  SurveyRequest longer = test::meadow_request(60);
  longer.endurance_s = 300;
  try {
    plan_survey(longer);
    ADD_FAILURE() << "a flight longer than its 300 s endurance was planned";
  } catch (const base::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("longer than the 4 min 00 s its battery gives less the "
                                         "20 % reserve"),
              std::string::npos)
        << e.what();
    const auto& remedies = e.remedies();
    EXPECT_NE(std::find(remedies.begin(), remedies.end(), base::Remedy::sorties), remedies.end());
  }
  // A swapped home is refused with the reading that lies at the area.
  SurveyRequest swapped = test::meadow_request(60);
  swapped.home = GeoPoint{8.5405, 47.3965, 0};
  try {
    plan_survey(swapped);
    ADD_FAILURE() << "a swapped home was planned";
  } catch (const base::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("latitude and longitude swapped"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(duration_text(3725), "1:02:05");
}

}  // namespace
}  // namespace swath::planning
