// Separation (docs/swath-fleet.md, "Safety envelope"): the rule that, with the altitude layers,
// keeps airborne drones at least separation_m apart.
//
// Why it holds. Every leg is flown at the drone's own layer and layers are separation_m apart, so
// two drones at their layers are apart; what is left is a drone crossing the layers below its
// own: climbing from its home to its layer, or descending from it to land at home. Each airborne
// drone has a *prediction*: its current leg (and, on a way round the fence, the legs to the
// route's later stops, each from rest), then hovering where it ends (or where it is). A drone's
// plan changes only by a new leg, a stop or its landing, and each is allowed only when it is
// clear: (a) its new path keeps separation_m from every drone now climbing or landing, until
// that climb or descent ends, and (b) a path that begins with a climb or is a landing keeps
// separation_m, during the climb or descent, from the prediction of every airborne drone. A plan
// that is not clear is not begun: the drone keeps the one it has (its leg, or hovering; on the
// ground it stays there; over its home it holds at its altitude) and asks again at the next
// tick. So while a drone climbs or lands, every other airborne drone follows a path that was
// checked against it. Positions are compared every dt = 0.05 s: between two samples their
// distance r changes no faster than V = v₁ + v₂, the two drones' top speeds in that interval
// (0 hovering, the climb or descent speed in a vertical part, else the fastest of cruise, climb
// and descent), so it stays at least (r₀ + r₁ − V dt) / 2, which must be separation_m. A drone
// straight above one that descends vertically hovers, V is the descent speed, and r grows from
// the layers' separation_m: the lowest of the drones over one home may always land.

#include "runtime/runtime_impl.hpp"

namespace swath::fleet::rt {

namespace {

constexpr double kSample_s = 0.05;

// A leg through the layers below the drone's own: a climb, or the landing's descent to the
// ground (the only legs that leave a layer; a level leg's rounding in height is neither).
bool crosses_layers(const Leg& leg) {
  return leg.climbing() || (leg.to().z <= 0 && leg.from().z > 0);
}

// Seconds of climb or landing descent left for a drone at `now_s`; 0 when it is doing neither.
double vertical_left_s(const Drone& d, double now_s) {
  if (!on_leg(d.mode) || !d.leg || !crosses_layers(*d.leg)) return 0.0;
  return std::max(0.0, d.leg->vertical_s() - (now_s - d.leg_start));
}

double top_speed_m_s(const Kinematics& k) {
  return std::max({k.cruise_m_s, k.climb_m_s, k.descent_m_s});
}

// The fastest a drone flying `leg` (then the stops of `rest`) since leg time `a_s` moves until
// `b_s`: 0 once the way is flown (it hovers), the vertical speed within the leg's climb or
// descent, else its top speed.
double way_speed_m_s(const Leg& leg, bool more_stops, double a_s, double b_s, const Kinematics& k) {
  if (!more_stops && a_s >= leg.duration_s()) return 0.0;
  if (b_s <= leg.vertical_s()) return leg.climbing() ? k.climb_m_s : k.descent_m_s;
  return top_speed_m_s(k);
}

// Drone j's speed bound on [a_s, b_s] as the runtime predicts it (position_at): its way, or
// hovering where it is; a vehicle that reports its place may be anywhere its speed takes it.
double speed_m_s(const Drone& j, double a_s, double b_s) {
  if (j.reported) return top_speed_m_s(j.spec.kinematics());
  if (!on_leg(j.mode) || !j.leg) return 0.0;
  return way_speed_m_s(*j.leg, !j.route.empty(), a_s - j.leg_start, b_s - j.leg_start,
                       j.spec.kinematics());
}

}  // namespace

Way Runtime::candidate_leg(const Drone& d, const Vec3& to, double t) const {
  const Leg* current = on_leg(d.mode) && d.leg ? &*d.leg : nullptr;
  Vec3 from = position_at(d, t);
  if (d.mode == Mode::landed || d.mode == Mode::charging) from.z = 0;
  // Round the fence: the whole way is the plan checked (a bend is no new plan).
  std::vector<Vec3> way = stops(from, to);
  const Vec3 first = way.front();
  way.erase(way.begin());
  return {next_leg(current, t - d.leg_start, from, first, d.spec.kinematics()), std::move(way)};
}

bool Runtime::clear_to_fly(const Drone& d, const std::optional<Way>& way, double t0) const {
  const double sep_m = settings_.envelope.separation_m;
  const Vec3 here = position_at(d, t0);
  const Kinematics& k = d.spec.kinematics();
  const auto mine = [&](double t) {
    return way ? way_position(way->leg, way->rest, t - t0, k) : here;
  };
  const Leg* leg = way ? &way->leg : nullptr;
  const auto my_speed_m_s = [&](double a_s, double b_s) {
    return way ? way_speed_m_s(way->leg, !way->rest.empty(), a_s - t0, b_s - t0, k) : 0.0;
  };
  const auto gap_m = [&](const Drone& j, double t) {
    const Vec3 a = mine(t), b = position_at(j, t);
    return std::hypot(a.x - b.x, a.y - b.y, a.z - b.z);
  };
  // The least distance the interval's ends and speeds allow (the header's bound); 1 µm for the
  // rounding of a drone straight above a vertical descent, where the bound is exact.
  const auto apart_until = [&](const Drone& j, double end_s) {
    double t = now_, r0_m = gap_m(j, t);
    if (r0_m < sep_m - 1e-6) return false;
    while (t < end_s) {
      const double t1 = std::min(end_s, t + kSample_s), r1_m = gap_m(j, t1);
      const double v_m_s = my_speed_m_s(t, t1) + speed_m_s(j, t, t1);
      if ((r0_m + r1_m - v_m_s * (t1 - t)) / 2 < sep_m - 1e-6) return false;
      t = t1, r0_m = r1_m;
    }
    return true;
  };
  const double my_vertical_end_s =
      leg && crosses_layers(*leg) && leg->vertical_s() > 0 ? t0 + leg->vertical_s() : -kInf;
  for (const Drone& j : drones_) {
    if (&j == &d || !airborne(j)) continue;
    if (const double left_s = vertical_left_s(j, now_);
        left_s > 0 && !apart_until(j, now_ + left_s))
      return false;                                                                    // (a)
    if (my_vertical_end_s > now_ && !apart_until(j, my_vertical_end_s)) return false;  // (b)
  }
  return true;
}

}  // namespace swath::fleet::rt
