// Relief (docs/swath-fleet.md).

#include "runtime/runtime_impl.hpp"

namespace swath::fleet::rt {

// ---- relief (docs/swath-fleet.md) ---------------------------------------------------
// A drone at work that must soon head home is relieved: the idle drone that gets to its place
// soonest is sent there when the working drone's leave time is within that flight plus
// relief_margin_s, and waits there, out of the scheduler's hands, until the working drone leaves
// (home, lost, link down). Then the stand-by is the drone nearest the work it left (requeued on
// the way home): the scheduler gives it the next segment without a flight from home.

bool Runtime::working(const Drone& d) const {
  return d.link_up && (d.task >= 0 || d.held_for >= 0) &&
         (d.mode == Mode::flying || d.mode == Mode::acting || d.mode == Mode::held ||
          d.mode == Mode::hovering);
}

bool Runtime::idle(const Drone& d) const {
  return d.link_up && d.sensor_ok && d.task < 0 && d.held_for < 0 && !d.spot && d.relieving < 0 &&
         !std::isfinite(d.home_retry_s) && (d.mode == Mode::landed || d.mode == Mode::hovering);
}

void Runtime::relieve() {
  next_relief_s_ = kInf;
  for (Drone& e : drones_) {  // stand-bys whose drone has left are free again
    if (e.relieving < 0) continue;
    const Drone& d = drones_[static_cast<std::size_t>(e.relieving)];
    if (!d.link_up || d.mode == Mode::returning || d.mode == Mode::landed ||
        d.mode == Mode::charging || d.mode == Mode::lost) {
      e.relieving = -1;
      changed_ = true;
    }
  }
  for (const Drone& d : drones_) {
    if (!working(d) || std::any_of(drones_.begin(), drones_.end(),
                                   [&](const Drone& e) { return e.relieving == d.index; }))
      continue;
    const double leave_s = must_leave_at(d);
    if (!std::isfinite(leave_s)) continue;
    Vec3 at = d.leg && on_leg(d.mode) ? way_end(d) : position_at(d, now_);
    Drone* best = nullptr;
    double best_eta = kInf;
    for (Drone& e : drones_) {
      if (&e == &d || !idle(e)) continue;
      const Vec3 to{at.x, at.y, e.layer_m};
      Vec3 from = position_at(e, now_);
      if (e.mode == Mode::landed) from.z = 0;
      // Its legs there and home inside the fence (as a scheduled drone's: Utility::pair_feasible).
      if (!settings_.envelope.reachable(from, to, e.spec.home_m)) continue;
      const double eta = way_s(e, from, to);
      // Worth it only when it can stay at least the margin beyond the hand-over.
      const double airborne_s = e.mode == Mode::landed ? now_ : e.airborne_since;
      if (leave_from(e, to, airborne_s, now_, eta) < leave_s + settings_.relief_margin_s) continue;
      if (eta < best_eta) best_eta = eta, best = &e;
    }
    if (!best) continue;
    const double when = leave_s - best_eta - settings_.relief_margin_s;
    if (when <= now_ + 1e-9)
      stand_by(*best, d, {at.x, at.y, best->layer_m}, leave_s);
    else
      next_relief_s_ = std::min(next_relief_s_, when);
  }
}

void Runtime::stand_by(Drone& e, const Drone& d, const Vec3& at, double leave_s) {
  if (!clear_to_fly(e, candidate_leg(e, at, now_), now_)) {  // separation: asked again next tick
    next_relief_s_ = std::min(next_relief_s_, now_ + settings_.tick_s);
    return;
  }
  e.relieving = d.index;
  ++record_.reliefs;
  log(at_json(json{{"ev", "relief"}, {"drone", e.index}, {"for", d.index}}, at,
              json{{"leave_s", round6(leave_s)}}));
  start_leg(e, at, Mode::positioning, now_);
}

}  // namespace swath::fleet::rt
