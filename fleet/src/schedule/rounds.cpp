// One scheduling round (docs/swath-fleet.md): the snapshot of requests and drones, the scheduler's
// assignment, its application to the fleet.

#include <chrono>

#include "runtime/runtime_impl.hpp"

namespace swath::fleet::rt {

// The scheduler's view of the fleet's kinematics and energy (the first drone's, eq. 12).
Snapshot Runtime::snapshot_base() const {
  Snapshot s;
  const DroneSpec& first = drones_.front().spec;
  const Kinematics k = first.kinematics();
  s.eta.cruise_m_s = k.cruise_m_s;
  s.eta.accel_m_s2 = k.accel_m_s2 > 0 ? k.accel_m_s2 : 1e9;
  s.eta.approach_m_s = k.approach_m_s;
  s.eta.approach_within_m = k.approach_within_m;
  s.weights = settings_.weights;
  s.fence = world_.fence();
  if (settings_.envelope.fenced()) s.envelope = envelope_;
  if (envelope_->routes()) s.eta.routes = envelope_.get();
  // Charge: there, serve, home above the reserve.
  EnergyFeasibility e;
  e.battery = first.battery;
  e.cruise_power_w = cruise_power_w(first, settings_.wind.velocity3_m_s());
  e.hover_power_w = hover_power_w(first, settings_.wind.velocity3_m_s());
  s.energy = e;
  return s;
}

// Requests: every running task with work whose head is not being acted on; `req_task` gets their
// task ids. First come, first served (paper 000 §4.1): a drone acting, held or bound for a place
// reserves a 5 m disc around it; other tasks' requests inside wait until it leaves.
void Runtime::add_requests(Snapshot& s, std::vector<int>& req_task) {
  std::vector<std::pair<Vec3, int>> discs;
  for (const Drone& d : drones_) {
    if (d.mode == Mode::acting || d.mode == Mode::held)
      discs.push_back({d.pos, d.mode == Mode::acting ? d.task : d.held_for});
    if (d.mode == Mode::flying && d.task >= 0 && d.leg) discs.push_back({way_end(d), d.task});
  }
  for (Task& t : tasks_) {
    if (!t.has_work()) continue;
    if (t.serving >= 0 && drones_[static_cast<std::size_t>(t.serving)].mode != Mode::flying)
      continue;
    const std::size_t h = t.head();
    Request r;
    r.location_m = t.actions[h].type == ActionType::fly_to ? t.actions[h].to : t.location;
    if (std::any_of(discs.begin(), discs.end(), [&](const std::pair<Vec3, int>& disc) {
          return disc.second != t.id &&
                 std::hypot(disc.first.x - r.location_m.x, disc.first.y - r.location_m.y) <
                     settings_.disc_m;
        }))
      continue;
    for (std::size_t i = h; i < t.actions.size(); ++i) {
      if (i > h && t.actions[i].type == ActionType::fly_to) break;
      r.service_s += t.actions[i].duration_s;
      if (t.actions[i].type == ActionType::sense) r.needs_sensor = true;
    }
    // Every segment is announced on its own (its own index, its wait counted from then): a head
    // that moved since the last announcement is the next segment, unless the segment was
    // requeued part-done (requeue() clears `requested`), which is announced again as itself.
    if (t.segment < 0 || (h != t.segment_head && t.requested)) {
      ++t.segment;
      t.requested = false;
    }
    t.segment_head = h;
    if (!t.requested) {
      t.requested = true;
      t.visible_since_s = now_;
      t.unserved_since_s = kInf;
      log(at_json(json{{"ev", "request_visible"}, {"task", t.id}, {"segment", t.segment}},
                  r.location_m, json{{"service_s", round6(r.service_s)}}));
      note_hits(r.location_m, t.id);
    }
    r.waiting_s = now_ - t.visible_since_s;
    if (t.bound) r.bound_drone = *t.bound;
    req_task.push_back(t.id);
    s.requests.push_back(r);
  }
}

// Drones available to the scheduler; `drone_of` maps snapshot drones to fleet indices. Bound
// requests are renumbered from fleet indices to snapshot positions.
void Runtime::add_drones(Snapshot& s, const std::vector<int>& req_task,
                         std::vector<int>& drone_of) {
  for (Drone& d : drones_) {
    if (!available(d) || d.relieving >= 0) continue;  // a stand-by is pinned to its place
    if (std::isfinite(d.home_retry_s)) continue;      // it is waiting to head home
    // On the ground with its climb not clear (separation.cpp): not offered this round, so the
    // scheduler does not keep giving it work it cannot start.
    if (d.mode == Mode::landed &&
        !clear_to_fly(d, candidate_leg(d, {d.spec.home_m.x, d.spec.home_m.y, d.layer_m}, now_),
                      now_)) {
      retry_s_ = std::min(retry_s_, now_ + settings_.tick_s);
      continue;
    }
    DroneState ds;
    ds.position_m = position_at(d, now_);
    if (!(ds.position_m.z > 0)) ds.position_m.z = d.layer_m;
    ds.home_m = {d.spec.home_m.x, d.spec.home_m.y, d.layer_m};
    ds.soc = d.soc;
    ds.can_sense = d.sensor_ok;
    if (d.mode == Mode::landed) ds.takeoff_s = d.layer_m / d.spec.kinematics().climb_m_s;
    if (std::isfinite(d.spec.max_flight_time_s)) {
      // What is left once the descent at home and two ticks of margin are set aside.
      const double used = d.mode == Mode::landed ? 0.0 : now_ - d.airborne_since;
      const double climb = d.mode == Mode::landed ? d.layer_m / d.spec.kinematics().climb_m_s : 0.0;
      ds.remaining_flight_s = d.spec.max_flight_time_s - used - climb -
                              d.layer_m / d.spec.kinematics().descent_m_s - 2 * settings_.tick_s;
    }
    if (d.mode == Mode::held) ds.only_request = -1;
    for (std::size_t r = 0; r < req_task.size(); ++r) {
      if (req_task[r] == d.task) ds.target = static_cast<int>(r);
      if (d.mode == Mode::held && req_task[r] == d.held_for) ds.only_request = static_cast<int>(r);
    }
    if (d.spot) {  // speculating: the forecast at its place is its target (commitment)
      double nearest = settings_.hit_within_m;
      for (std::size_t f = 0; f < s.forecasts.size(); ++f)
        if (const double g = vehicle::horizontal_distance(s.forecasts[f].location_m, *d.spot);
            g <= nearest) {
          nearest = g;
          ds.target = static_cast<int>(req_task.size() + f);
        }
    }
    drone_of.push_back(d.index);
    s.drones.push_back(ds);
  }
  // Where the airborne drones land (scheduler.hpp, LandingColumn).
  s.column_radius_m = settings_.envelope.separation_m;
  for (const Drone& d : drones_)
    if (airborne(d)) {
      const auto it = std::find(drone_of.begin(), drone_of.end(), d.index);
      s.landing_columns.push_back(
          {{d.spec.home_m.x, d.spec.home_m.y, d.layer_m},
           it == drone_of.end() ? -1 : static_cast<int>(it - drone_of.begin())});
    }
  for (Request& r : s.requests)
    if (r.bound_drone) {
      auto it = std::find(drone_of.begin(), drone_of.end(), *r.bound_drone);
      r.bound_drone = it == drone_of.end() ? -1 : static_cast<int>(it - drone_of.begin());
    }
}

// Applies the difference to the fleet. Two requests of this round inside one disc: the first (by
// drone) goes. Drones that lost their request to another and got nothing stop where they are.
void Runtime::apply_assignment(const Snapshot& s, const Assignment& a,
                               const std::vector<int>& req_task, const std::vector<int>& drone_of) {
  std::vector<Vec3> claimed;
  const auto visible = static_cast<int>(req_task.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    Drone& d = drones_[static_cast<std::size_t>(drone_of[i])];
    if (a[i] && *a[i] >= visible) {  // speculation: only a place to wait at
      const ForecastRequest& f = s.forecasts[static_cast<std::size_t>(*a[i] - visible)];
      if (d.spot && vehicle::horizontal_distance(*d.spot, f.location_m) < 1e-6) continue;
      const Vec3 to{f.location_m.x, f.location_m.y, d.layer_m};
      if (!clear_to_fly(d, candidate_leg(d, to, now_), now_)) {  // separation: not now
        retry_s_ = std::min(retry_s_, now_ + settings_.tick_s);
        continue;
      }
      unserve(d);
      position(d, f);
      continue;
    }
    leave_spot(d);
    int want = a[i] ? req_task[static_cast<std::size_t>(*a[i])] : -1;
    if (want >= 0) {
      const Vec3 at = s.requests[static_cast<std::size_t>(*a[i])].location_m;
      if (std::any_of(claimed.begin(), claimed.end(), [&](const Vec3& c) {
            return std::hypot(c.x - at.x, c.y - at.y) < settings_.disc_m;
          })) {
        want = d.task;  // keeps what it had; the request waits for the disc
        changed_ = true;
      } else {
        claimed.push_back(at);
      }
    }
    if (want == d.task) continue;
    if (want >= 0 &&
        !clear_to_fly(
            d, candidate_leg(d, dispatch_target(d, tasks_[static_cast<std::size_t>(want)]), now_),
            now_)) {  // separation: it keeps its plan, asked again next tick
      retry_s_ = std::min(retry_s_, now_ + settings_.tick_s);
      continue;
    }
    if (d.task >= 0) {  // retargeted or stopped on the way
      unserve(d);
      if (want < 0) stop(d, now_);
    }
    if (want >= 0) {
      Task& t = tasks_[static_cast<std::size_t>(want)];
      if (t.serving >= 0 && t.serving != d.index) {
        Drone& other = drones_[static_cast<std::size_t>(t.serving)];
        if (other.task == t.id) other.task = -1;
      }
      dispatch(d, t, now_);
    }
  }
  for (Drone& d : drones_)
    if ((d.mode == Mode::flying && d.task < 0) ||
        (d.mode == Mode::positioning && !d.spot && d.relieving < 0))
      stop(d, now_);
}

// One scheduling round (docs/swath-fleet.md, 'Scheduling'): the snapshot, the scheduler's
// assignment (timed), its log line, its application.
void Runtime::schedule() {
  Snapshot s = snapshot_base();
  std::vector<int> req_task, drone_of;
  update_forecasts();
  add_requests(s, req_task);
  add_forecasts(s, req_task);
  add_drones(s, req_task, drone_of);
  if (s.requests.empty() && s.forecasts.empty() &&
      std::none_of(s.drones.begin(), s.drones.end(),
                   [](const DroneState& x) { return x.target.has_value(); }))
    return;
  const auto clock0 = std::chrono::steady_clock::now();
  const Assignment a = s.drones.empty() ? Assignment{} : scheduler_->assign(s, sched_rng_);
  record_.decision_s_total +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock0).count();
  ++record_.schedules;
  json assignment = json::array();
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!a[i]) continue;
    const auto k = static_cast<std::size_t>(*a[i]);
    if (k < req_task.size())
      assignment.push_back(json{{"drone", drone_of[i]}, {"task", req_task[k]}});
    else  // a forecast place (its `position` event follows)
      assignment.push_back(json{{"drone", drone_of[i]}, {"forecast", k - req_task.size()}});
  }
  log(json{{"ev", "schedule"}, {"assignment", assignment}});
  note_unserved(s, a, req_task);
  apply_assignment(s, a, req_task, drone_of);
}

// The no-feasible-drone clock of each visible request (docs/swath-fleet.md): it runs while a
// round leaves a drone free (nothing, or only a forecast place: a request it could serve would
// outrank that) and the request without a drone, or no drone is left to fly at all; it stops
// when the request is given to a drone or every drone is busy (a held drone, or one kept for its
// non-interruptible task, is not free). A request that waits for busy drones never fails for that.
void Runtime::note_unserved(const Snapshot& s, const Assignment& a,
                            const std::vector<int>& req_task) {
  const auto visible = static_cast<int>(req_task.size());
  std::vector<char> given(req_task.size(), 0);
  bool free_drone = false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] && *a[i] < visible)
      given[static_cast<std::size_t>(*a[i])] = 1;
    else if (!s.drones[i].only_request)
      free_drone = true;
  }
  const bool none_left = std::all_of(drones_.begin(), drones_.end(),
                                     [](const Drone& d) { return d.mode == Mode::lost; });
  for (std::size_t k = 0; k < req_task.size(); ++k) {
    Task& t = tasks_[static_cast<std::size_t>(req_task[k])];
    if (given[k] || !(free_drone || none_left))
      t.unserved_since_s = kInf;
    else if (!std::isfinite(t.unserved_since_s))
      t.unserved_since_s = now_;
  }
}

}  // namespace swath::fleet::rt
