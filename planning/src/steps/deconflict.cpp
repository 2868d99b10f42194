// Step 7a of plan_survey(): the drones of one plan kept kSeparation_m apart (survey_steps.hpp):
// altitude layers for drones whose paths come near each other, staggered launches where one climbs
// or descends through another's layer near its home.
#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/planning/survey_steps.hpp"

namespace swath::planning::steps {
namespace {

using geometry::Point2;

// Every flight of a drone (its sorties, or the whole flight).
std::vector<const DroneMission*> flights(const DronePlan& d) {
  if (d.sorties.empty()) return {&d.mission};
  std::vector<const DroneMission*> out;
  for (const Sortie& s : d.sorties) out.push_back(&s.mission);
  return out;
}

struct Box {
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  void add(Point2 p) {
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  }
  double gap_m(const Box& o) const {
    return std::hypot(std::max({0.0, o.x0 - x1, x0 - o.x1}), std::max({0.0, o.y0 - y1, y0 - o.y1}));
  }
};

// The least distance between the legs a-b and c-d, metres (0 when they cross).
double legs_apart_m(Point2 a, Point2 b, Point2 c, Point2 d) {
  if (geometry::segments_intersect(a, b, c, d)) return 0.0;
  return std::min({geometry::distance_to_segment(a, c, d), geometry::distance_to_segment(b, c, d),
                   geometry::distance_to_segment(c, a, b), geometry::distance_to_segment(d, a, b)});
}

// Whether two drones' flown paths (every leg, homes included) come within `near_m` of each other
// anywhere, whenever: checked leg against leg, legs whose boxes are farther apart skipped.
bool paths_near(const DronePlan& a, const DronePlan& b, double near_m) {
  for (const DroneMission* fa : flights(a))
    for (const DroneMission* fb : flights(b))
      for (std::size_t i = 0; i + 1 < fa->path.size(); ++i) {
        Box la;
        la.add(fa->path[i]);
        la.add(fa->path[i + 1]);
        for (std::size_t j = 0; j + 1 < fb->path.size(); ++j) {
          Box lb;
          lb.add(fb->path[j]);
          lb.add(fb->path[j + 1]);
          if (la.gap_m(lb) >= near_m) continue;
          if (legs_apart_m(fa->path[i], fa->path[i + 1], fb->path[j], fb->path[j + 1]) < near_m)
            return true;
        }
      }
  return false;
}

// The layer of each drone: the lowest not taken by an earlier drone whose path comes near its own
// (greedy colouring in fleet order). Near: kSeparation_m, plus the corners autopilots cut and the
// overrun past a stop at the faster drone's speed.
std::vector<int> layers(const SurveyPlan& plan) {
  const std::size_t n = plan.drones.size();
  std::vector<int> layer(n, 0);
  for (std::size_t i = 1; i < n; ++i) {
    std::vector<char> taken(n, 0);
    for (std::size_t j = 0; j < i; ++j) {
      const double fastest = std::max(plan.drones[i].speed_m_s, plan.drones[j].speed_m_s);
      const double near_m = kSeparation_m + 2 * kCornerAllowance_m + stop_overrun_m(fastest);
      if (paths_near(plan.drones[i], plan.drones[j], near_m))
        taken[static_cast<std::size_t>(layer[j])] = 1;
    }
    while (taken[static_cast<std::size_t>(layer[i])]) ++layer[i];
  }
  return layer;
}

// One flight's legs as time windows: [from_s, to_s] of its own clock (0 = its launch) over each
// leg, the climb at home first and the descent last; the legs' times scaled so that the whole
// takes the mission's estimate (which counts the stops and accelerations).
struct Leg {
  double from_s, to_s;
  Point2 a, b;
};
std::vector<Leg> timeline(const DronePlan& d, const DroneMission& m) {
  const double altitude_m = m.items.empty() ? 0.0 : m.items.front().altitude_m;
  const double climb_s = altitude_m / d.climb_speed_m_s,
               descent_s = altitude_m / d.descent_speed_m_s;
  const double cruise_s =
      std::max(m.path_length_m / d.speed_m_s, m.flight_time_s - climb_s - descent_s);
  const double scale = m.path_length_m > 0 ? cruise_s / m.path_length_m : 0.0;
  std::vector<Leg> out{{0.0, climb_s, m.home, m.home}};
  double now = climb_s;
  for (std::size_t i = 0; i + 1 < m.path.size(); ++i) {
    const double dt = geometry::distance(m.path[i], m.path[i + 1]) * scale;
    out.push_back({now, now + dt, m.path[i], m.path[i + 1]});
    now += dt;
  }
  out.push_back({now, now + descent_s, m.home, m.home});
  return out;
}

struct Window {
  double from_s, to_s;
};

// When (its own clock) the drone is within `near_m` of `p` horizontally, windows per leg.
std::vector<Window> near_point(const std::vector<Leg>& legs, Point2 p, double near_m) {
  std::vector<Window> out;
  for (const Leg& l : legs)
    if (geometry::distance_to_segment(p, l.a, l.b) < near_m) out.push_back({l.from_s, l.to_s});
  return out;
}

bool overlap(const std::vector<Window>& a, double shift_a, const std::vector<Window>& b,
             double shift_b, double slack_s) {
  for (const Window& x : a)
    for (const Window& y : b)
      if (x.from_s + shift_a - slack_s < y.to_s + shift_b &&
          y.from_s + shift_b - slack_s < x.to_s + shift_a)
        return true;
  return false;
}

// How much the flight's estimate (stops, accelerations) exceeds flying it at constant speed,
// seconds: how far its time near any point may be off either way.
double unsure_s(const DronePlan& d, const DroneMission& m) {
  const double altitude_m = m.items.empty() ? 0.0 : m.items.front().altitude_m;
  const double constant_s = altitude_m / d.climb_speed_m_s + m.path_length_m / d.speed_m_s +
                            altitude_m / d.descent_speed_m_s;
  return std::max(0.0, m.flight_time_s - constant_s);
}

// One flight of a drone (the whole flight, or one sortie) on the drone's layer.
struct TimedFlight {
  std::size_t drone;
  std::size_t sortie;  ///< 0 for the first (or only) flight of its drone
  int layer;
  std::vector<Leg> legs;
  double unsure_s;
  double end_s() const { return legs.back().to_s; }
};

std::vector<TimedFlight> timed_flights(const SurveyPlan& plan, const std::vector<int>& layer) {
  std::vector<TimedFlight> out;
  for (std::size_t i = 0; i < plan.drones.size(); ++i)
    for (const DroneMission* m : flights(plan.drones[i]))
      out.push_back({i, out.empty() || out.back().drone != i ? 0 : out.back().sortie + 1, layer[i],
                     timeline(plan.drones[i], *m), unsure_s(plan.drones[i], *m)});
  return out;
}

// Whether the higher of two flights of different layers, launched at their offsets, climbs or
// descends at its home while the lower is near that home; windows widened by 15 s, 5 % of the
// longer flight and the larger unsure_s() for the timing the estimate may get wrong.
bool clash(const SurveyPlan& plan, const TimedFlight& f, double f_s, const TimedFlight& g,
           double g_s) {
  const bool f_high = f.layer > g.layer;
  const TimedFlight& hi = f_high ? f : g;
  const TimedFlight& lo = f_high ? g : f;
  const double near_m = kSeparation_m + kCornerAllowance_m;
  const double slack_s =
      15 + 0.05 * std::max(f.end_s(), g.end_s()) + std::max(f.unsure_s, g.unsure_s);
  const std::vector<Window> column{{hi.legs.front().from_s, hi.legs.front().to_s},
                                   {hi.legs.back().from_s, hi.legs.back().to_s}};
  return overlap(column, f_high ? f_s : g_s,
                 near_point(lo.legs, plan.drones[hi.drone].home, near_m), f_high ? g_s : f_s,
                 slack_s);
}

// Between a drone's sorties: the pilot lands it, swaps its battery and arms it again, seconds.
constexpr double kBatteryChange_s = 120.0;

// Launch offsets of every flight: a drone climbs and descends at its home through every lower
// layer, so no drone of a lower layer may be near that home then. Flights are placed round by
// round (every drone's first sortie, then every second one, ...: sorties interleave instead of
// one drone's all waiting for another's), lowest layer first within a round, each at the first
// 10 s step where its climb and descent miss every placed lower flight's time near its home and
// every placed higher flight's climb and descent miss its own time near theirs. A sortie launches
// no earlier than the one before it lands by the estimate plus what that estimate may be short
// (5 % and its unsure_s()), and the battery change after it: a late landing would otherwise shift
// it out of its slot, and a pilot needs the time to land, swap and arm (kBatteryChange_s).
std::vector<double> launch_offsets(const SurveyPlan& plan, const std::vector<TimedFlight>& all) {
  const std::size_t n = all.size();
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::tie(all[a].sortie, all[a].layer) < std::tie(all[b].sortie, all[b].layer);
  });
  std::vector<double> offset(n, 0.0);
  std::vector<std::size_t> placed;
  for (const std::size_t i : order) {
    int first_step = 0;
    if (i > 0 && all[i - 1].drone == all[i].drone) {  // a later sortie: placed after its previous
      const TimedFlight& before = all[i - 1];
      const double landed_s =
          offset[i - 1] + 1.05 * before.end_s() + before.unsure_s + kBatteryChange_s;
      first_step = static_cast<int>(std::ceil(landed_s / 10.0 - 1e-9));
    }
    for (int step = first_step; step < first_step + 10'000; ++step) {
      offset[i] = 10.0 * step;
      const bool any = std::any_of(placed.begin(), placed.end(), [&](std::size_t j) {
        // same layer: apart everywhere, whenever (layers())
        return all[i].layer != all[j].layer && clash(plan, all[i], offset[i], all[j], offset[j]);
      });
      if (!any) break;
    }
    placed.push_back(i);
  }
  return offset;
}

void raise(DroneMission& m, double by_m, const DronePlan& d) {
  for (MissionItem& item : m.items)
    if (positional(item.kind) && item.kind != ItemKind::land) item.altitude_m += by_m;
  m.flight_time_s += by_m / d.climb_speed_m_s + by_m / d.descent_speed_m_s;
}

}  // namespace

void deconflict(SurveyPlan& plan) {
  if (plan.drones.size() < 2) return;
  const std::vector<int> layer = layers(plan);
  const int top = *std::max_element(layer.begin(), layer.end());
  const double spacing_m = plan.request.layer_spacing_m;
  const double highest_m = plan.imaging.altitude_m + top * spacing_m;
  if (top > 0 && highest_m > plan.request.ceiling_m + 1e-9)
    throw base::InputError("the " + std::to_string(plan.drones.size()) + " drones need " +
                           std::to_string(top + 1) + " altitude layers " +
                           base::fixed_text(spacing_m, 1) + " m apart to keep " +
                           base::fixed_text(kSeparation_m, 0) + " m from each other, up to " +
                           base::fixed_text(highest_m, 1) + " m, above the ceiling of " +
                           base::fixed_text(plan.request.ceiling_m, 1) +
                           " m; give a lower --altitude, a smaller --layer-spacing, a higher "
                           "--ceiling or fewer drones");
  for (std::size_t i = 0; i < plan.drones.size(); ++i) {
    DronePlan& d = plan.drones[i];
    d.layer_m = layer[i] * spacing_m;
    if (d.layer_m == 0) continue;
    raise(d.mission, d.layer_m, d);
    for (Sortie& s : d.sorties) raise(s.mission, d.layer_m, d);
  }
  const std::vector<TimedFlight> all = timed_flights(plan, layer);
  const std::vector<double> offset = launch_offsets(plan, all);
  for (std::size_t k = 0; k < all.size(); ++k) {
    DronePlan& d = plan.drones[all[k].drone];
    if (all[k].sortie == 0) d.launch_offset_s = offset[k];
    if (!d.sorties.empty()) d.sorties[all[k].sortie].launch_offset_s = offset[k];
  }
}

}  // namespace swath::planning::steps
