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
// checked against it. Positions are compared every dt = 0.05 s with a margin of (v₁ + v₂) dt / 2
// (no drone is faster than its cruise, climb or descent speed: 0.5 m at 10 m/s), so nothing
// between two samples comes nearer.

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

double top_speed_m_s(const Drone& d) {
  const Kinematics& k = d.spec.kinematics();
  return std::max({k.cruise_m_s, k.climb_m_s, k.descent_m_s});
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
  const auto apart_until = [&](const Drone& j, double end_s) {
    const double margin_m = (top_speed_m_s(d) + top_speed_m_s(j)) * kSample_s / 2;
    for (double t = now_;; t = std::min(end_s, t + kSample_s)) {
      const Vec3 a = mine(t), b = position_at(j, t);
      if (std::hypot(a.x - b.x, a.y - b.y, a.z - b.z) < sep_m + margin_m) return false;
      if (t >= end_s) return true;
    }
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
