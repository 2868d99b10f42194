// The runtime's record of each drone: its mode, its legs, its actions, the results it sends.

#include "runtime/runtime_impl.hpp"

namespace swath::fleet::rt {

Vec3 Runtime::position_at(const Drone& d, double t) const {
  if (d.reported && d.mode != Mode::charging && d.mode != Mode::landed) return *d.reported;
  if (on_leg(d.mode) && d.leg)
    return way_position(*d.leg, d.route, t - d.leg_start, d.spec.kinematics());
  return d.pos;
}

void Runtime::set_mode(Drone& d, Mode m, double t) {
  d.mode = m;
  const std::string name = mode_name(m, d.link_up);
  if (name != d.span_mode) {
    if (!d.span_mode.empty() && t > d.span_start)
      d.record.spans.push_back({round6(d.span_start), round6(t), d.span_mode});
    d.span_mode = name;
    d.span_start = t;
  }
  d.record.track.push_back({round6(t), round6(d.pos.x), round6(d.pos.y), round6(d.pos.z)});
  // Every point of the track and every change of mode, so that `swath-fleet render` redraws the
  // run from its events alone (the state's own time: a leg may end between ticks).
  log(at_json(json{{"ev", "drone_mode"}, {"drone", d.index}, {"at_s", round6(t)}}, d.pos,
              json{{"state", name}}));
}

double Runtime::next_event(const Drone& d) const {
  double e = kInf;
  switch (d.mode) {
    case Mode::flying:
    case Mode::positioning:
      e = backend_.arrival_s(d.index);  // infinity when the vehicle's report ends it
      break;
    case Mode::returning:  // holding over home, it asks for its descent again then
      e = std::isfinite(d.land_retry_s) ? d.land_retry_s : backend_.arrival_s(d.index);
      break;
    case Mode::acting:
      e = d.act_end;
      break;
    case Mode::charging:
      e = d.charge_end;
      break;
    case Mode::held:
      e = d.hold_until;
      break;
    default:
      break;
  }
  if (!d.link_up) e = std::min(e, d.link_back);
  if (!d.sensor_ok) e = std::min(e, d.sensor_back);
  e = std::min(e, exhausted_at(d));
  if (std::isfinite(d.home_retry_s)) return std::min(e, d.home_retry_s);  // instead of leaving
  return std::min(e, leave_time(d));
}

std::vector<Vec3> Runtime::stops(const Vec3& from, const Vec3& to) const {
  std::vector<Vec3> way = settings_.envelope.route(from, to);
  if (way.empty()) way = {to};
  return way;
}

double Runtime::way_s(const Drone& d, const Vec3& from, const Vec3& to) const {
  double s = 0;
  Vec3 at = from;
  for (const Vec3& stop : stops(from, to)) {
    s += Leg(at, stop, d.spec.kinematics()).duration_s();
    at = stop;
  }
  return s;
}

// A leg round the fence is flown stop by stop (each a straight leg), the target last.
void Runtime::start_leg(Drone& d, const Vec3& to, Mode mode, double t) {
  integrate(d, t);
  const std::vector<Vec3> way = stops(d.pos, to);
  d.route.assign(way.begin() + 1, way.end());
  fly_leg(d, way.front(), mode, t);
}

void Runtime::fly_leg(Drone& d, const Vec3& to, Mode mode, double t) {
  const Leg* current = on_leg(d.mode) && d.leg ? &*d.leg : nullptr;
  if (d.mode == Mode::landed) d.airborne_since = t;
  d.leg = next_leg(current, t - d.leg_start, d.pos, to, d.spec.kinematics());
  d.leg_start = t;
  set_mode(d, mode, t);  // logs the stop: `check` judges the legs between logged positions
  command_leg(d, to, mode, t);
}

// A bend of the drone's route reached (it stopped there): on to the next stop.
void Runtime::next_stop(Drone& d, double t) {
  integrate(d, t);
  d.pos = d.reported ? *d.reported : d.leg->to();
  const Vec3 to = d.route.front();
  d.route.erase(d.route.begin());
  fly_leg(d, to, d.mode, t);
}

// The vehicle is told to fly what the model just started (the simulated fleet starts the same
// leg); on the way home, the route's bends are flown as legs and the last one as the return. A
// model flies that last one to above home like any leg: its landing is the runtime's (descend).
void Runtime::command_leg(Drone& d, const Vec3& to, Mode mode, double t) {
  if (mode == Mode::returning && d.route.empty() && backend_.reports_every_tick()) {
    backend_.return_home(d.index, t);
    return;
  }
  const Kinematics& k = d.spec.kinematics();
  backend_.go_to(d.index, t, to, k.cruise_m_s, k.approach_m_s, k.approach_within_m);
}

// The drone stops where it is and hovers (its request taken away or cancelled).
void Runtime::stop(Drone& d, double t) {
  integrate(d, t);
  // Hovering here must be clear of every climb (separation.cpp), and not between layers (it
  // finishes its climb first); else it flies on to the end of its leg (then hovers there, as
  // checked) and is asked again.
  if (d.leg && on_leg(d.mode) &&
      (d.pos.z < d.layer_m - 1e-6 || !clear_to_fly(d, std::nullopt, t))) {
    retry_s_ = std::min(retry_s_, t + settings_.tick_s);
    return;
  }
  d.leg.reset();
  d.route.clear();
  backend_.hold(d.index, t);
  set_mode(d, Mode::hovering, t);
}

bool Runtime::available(const Drone& d) const {
  return d.link_up && (d.mode == Mode::landed || d.mode == Mode::hovering || d.mode == Mode::held ||
                       d.mode == Mode::positioning || (d.mode == Mode::flying && d.task >= 0));
}

void Runtime::requeue(Drone& d, const std::string& reason) {
  if (d.task < 0) return;
  Task& t = tasks_[static_cast<std::size_t>(d.task)];
  unserve(d);
  t.requested = false;
  log(json{{"ev", "requeued"}, {"task", t.id}, {"drone", d.index}, {"reason", reason}});
  ++record_.requeued;
  changed_ = true;
}

// The drone no longer serves its task: the segment it was on waits for a drone again.
void Runtime::unserve(Drone& d) {
  if (d.task < 0) return;
  Task& t = tasks_[static_cast<std::size_t>(d.task)];
  for (auto& a : t.actions)
    if (a.state == ActionState::running) a.state = ActionState::pending;
  t.serving = -1;
  d.task = -1;
}

void Runtime::go_home(Drone& d, double t, const std::string& why) {
  requeue(d, why);
  leave_spot(d);
  d.relieving = -1;
  if (d.held_for >= 0) d.held_for = -1;
  integrate(d, t);
  // Home at its own layer: a drone climbing when sent home (a fault mid-climb) finishes its climb
  // first. Stopping between layers would put it in another drone's, which that drone's legs were
  // cleared against it leaving.
  const Vec3 home{d.spec.home_m.x, d.spec.home_m.y, d.layer_m};
  d.home_retry_s = kInf;
  // A real vehicle out of reach flies home by its own failsafe: nothing the runtime can hold.
  const bool failsafe = !d.link_up && backend_.reports_every_tick();
  if (!failsafe && !clear_to_fly(d, candidate_leg(d, home, t), t)) {  // next tick; as it is
    d.home_retry_s = t + settings_.tick_s;
    d.home_why = why;
    if (d.mode == Mode::acting || d.mode == Mode::held) set_mode(d, Mode::hovering, t);
    changed_ = true;
    return;
  }
  start_leg(d, home, Mode::returning, t);
  changed_ = true;
}

void Runtime::release(Drone& d, double t) {
  Task* t_ptr = d.task >= 0 ? &tasks_[static_cast<std::size_t>(d.task)] : nullptr;
  if (t_ptr) t_ptr->serving = -1;
  d.task = -1;
  if (t_ptr && !t_ptr->flags.interruptible && t_ptr->status == TaskStatus::running) {
    d.held_for = t_ptr->id;
    d.hold_until = t + settings_.hold_s;
    set_mode(d, Mode::held, t);
  } else {
    set_mode(d, Mode::hovering, t);
  }
  changed_ = true;
  if (must_go_home(d, t)) go_home(d, t, "battery");
}

// The drone is where its task's head segment is: do the next action, or finish the segment.
void Runtime::start_action_or_release(Drone& d, double t) {
  Task& tk = tasks_[static_cast<std::size_t>(d.task)];
  const std::size_t h = tk.head();
  if (tk.status != TaskStatus::running || h >= tk.actions.size() ||
      tk.actions[h].type == ActionType::fly_to || (tk.actions[h].state != ActionState::pending)) {
    release(d, t);
    return;
  }
  Action& a = tk.actions[h];
  if (a.type == ActionType::sense && !d.sensor_ok) {
    requeue(d, "sensor_failure");
    set_mode(d, Mode::hovering, t);
    return;
  }
  a.state = ActionState::running;
  d.action = h;
  d.act_end = t + a.duration_s;
  set_mode(d, Mode::acting, t);
  backend_.act(d.index, a.name, a.type == ActionType::sense);
}

// A link back or a sensor repaired by t.
void Runtime::recover(Drone& d, double t) {
  if (!d.link_up && t >= d.link_back) {
    d.link_up = true;
    for (Pending& p : d.buffered) {
      p.deliver_s = t + settings_.link_latency_s;
      pending_.push_back(p);
    }
    d.buffered.clear();
    set_mode(d, d.mode, t);
    changed_ = true;
  }
  if (!d.sensor_ok && t >= d.sensor_back) {
    d.sensor_ok = true;
    changed_ = true;
  }
}

// A result on its way to the app: after the link's latency, or buffered while the link is down.
void Runtime::emit(Drone& d, Task& tk, std::size_t a, const Reading& r, double t) {
  Pending p{t + settings_.link_latency_s, d.index, tk.id, a, r, seq_++};
  if (d.link_up)
    pending_.push_back(std::move(p));
  else
    d.buffered.push_back(std::move(p));
}

// fly_sensing: a reading every period along the leg that reached the target (x_m, y_m and the
// sensor's values per sample).
void Runtime::sample_along(const Action& fa, const Leg& flown, double flown_from, Reading& r) {
  r.sensor = fa.sample_sensor;
  std::string ref;
  for (double s_t = fa.sample_period_s;
       s_t <= flown.duration_s() + 1e-9 && r.values.size() < 3 * 100000;
       s_t += fa.sample_period_s) {
    const Vec3 at = flown.position_at(s_t);
    const Reading one = world_.sense(fa.sample_sensor, at, flown_from + s_t);
    r.values.push_back(at.x);
    r.values.push_back(at.y);
    r.values.insert(r.values.end(), one.values.begin(), one.values.end());
    ref = one.ref;
  }
  r.ref = "samples of x_m,y_m," + ref;
}

// The end of a leg to a task's place: the fly_to done (binding the task where its flags say),
// then its next action, or home when the link is down.
void Runtime::arrive(Drone& d, double t) {
  const Leg flown = *d.leg;
  const double flown_from = d.leg_start;
  d.pos = d.reported ? *d.reported : d.leg->to();
  d.leg.reset();
  if (d.task < 0) {
    set_mode(d, Mode::hovering, t);
    return;
  }
  Task& tk = tasks_[static_cast<std::size_t>(d.task)];
  if (std::find(tk.drones_used.begin(), tk.drones_used.end(), d.index) == tk.drones_used.end())
    tk.drones_used.push_back(d.index);
  if ((tk.flags.same_drone || !tk.flags.interruptible) && !tk.bound) tk.bound = d.index;
  const std::size_t h = tk.head();
  if (h < tk.actions.size() && tk.actions[h].type == ActionType::fly_to) {
    tk.actions[h].state = ActionState::completed;
    Reading r;
    r.t_s = t;
    r.drone = d.index;
    r.at = d.pos;
    r.sensor = "fly_to";
    if (tk.actions[h].sample_period_s > 0) try {
        sample_along(tk.actions[h], flown, flown_from, r);
      } catch (const SensorError& e) {
        fail_for_sensor(tk, e);
        return;
      }
    emit(d, tk, h, r, t);
  }
  if (!d.link_up) {  // the vehicle's own failsafe takes it home
    requeue(d, "link_loss");
    go_home(d, t, "link_loss");
    return;
  }
  start_action_or_release(d, t);
}

// A sensor that could not read fails its task as any failed action would, with the sensor's
// sentence (an app's own sensor: its file and line); the drone serving it is freed.
void Runtime::fail_for_sensor(Task& tk, const SensorError& e) {
  fail_action_futures(tk, std::make_exception_ptr(ActionFailed(e.what())));
  finish_task(tk, TaskStatus::failed, e.what());
}

// The end of an action: its reading, then the next action, or home (link down, battery).
void Runtime::finish_action(Drone& d, double t) {
  Task& tk = tasks_[static_cast<std::size_t>(d.task)];
  Action& a = tk.actions[d.action];
  a.state = ActionState::completed;
  Reading r;
  if (a.type == ActionType::sense) try {
      r = world_.sense(a.name, d.pos, t);
    } catch (const SensorError& e) {
      fail_for_sensor(tk, e);
      return;
    }
  r.t_s = t;
  r.drone = d.index;
  r.at = d.pos;
  if (r.sensor.empty()) r.sensor = a.name;
  emit(d, tk, d.action, r, t);
  if (!d.link_up) {
    go_home(d, t, "link_loss");
    return;
  }
  if (must_go_home(d, t)) {
    go_home(d, t, "battery");
    return;
  }
  start_action_or_release(d, t);
}

// Over home at the end of the way home (a model's vehicle): the landing, straight down at the
// descent speed, logged as it is flown. It is a new plan like a take-off's climb and begun only
// when clear of the other drones (separation.cpp); else the drone holds over its home at its
// altitude and asks again at the next tick (a drone landing near it lands first).
void Runtime::descend(Drone& d, double t) {
  integrate(d, t);
  d.pos = d.leg->to();
  const Way down{Leg(d.pos, {d.pos.x, d.pos.y, 0}, d.spec.kinematics()), {}};
  if (!clear_to_fly(d, down, t)) {
    if (!std::isfinite(d.land_retry_s)) backend_.hold(d.index, t);
    d.land_retry_s = t + settings_.tick_s;
    return;
  }
  d.land_retry_s = kInf;
  d.leg = down.leg;
  d.leg_start = t;
  set_mode(d, Mode::returning, t);  // logs the top of the descent
  backend_.land(d.index, t);
}

// Down at home: the recharge (a swap or a charge to full, case 5's 30 s). A vehicle that lands
// itself (a real one's return to launch) ends its model leg over home: its descent from there is
// counted here.
void Runtime::land_home(Drone& d, double t) {
  d.pos = d.leg->to();
  d.leg.reset();
  const double down = d.pos.z / d.spec.kinematics().descent_m_s;
  d.energy_j += descent_power_w(d.spec) * down;
  d.soc = vehicle::soc_after_charge(
      d.spec.battery, d.soc,
      energy::battery_current_a(d.spec.battery, descent_power_w(d.spec)) * down);
  d.flight_s += down;
  d.pos.z = 0;
  d.charge_end = t + d.spec.recharge_s;
  set_mode(d, Mode::charging, t);
  changed_ = true;
}

// Everything that happens to drone d at time t (an event of next_event(d)).
void Runtime::step_drone(Drone& d, double t) {
  integrate(d, t);
  recover(d, t);
  if (t >= exhausted_at(d) - 1e-9) {
    exhaust(d, t);
    return;
  }
  if (std::isfinite(d.home_retry_s) && t >= d.home_retry_s - 1e-9) {
    d.home_retry_s = kInf;
    if (d.mode != Mode::landed && d.mode != Mode::charging && d.mode != Mode::lost) {
      go_home(d, t, d.home_why);
      return;
    }
  }
  switch (d.mode) {
    case Mode::flying:
    case Mode::positioning:
      if (t < backend_.arrival_s(d.index)) break;
      if (d.route.empty())
        arrive(d, t);
      else
        next_stop(d, t);
      break;
    case Mode::acting:
      if (t >= d.act_end) finish_action(d, t);
      break;
    case Mode::returning:
      if (std::isfinite(d.land_retry_s)) {
        if (t >= d.land_retry_s - 1e-9) descend(d, t);
        break;
      }
      if (t < backend_.arrival_s(d.index)) break;
      if (!d.route.empty())
        next_stop(d, t);
      else if (d.leg->to().z > 0)
        descend(d, t);
      else
        land_home(d, t);
      break;
    case Mode::charging:
      if (t >= d.charge_end) {
        d.soc = 1.0;
        set_mode(d, Mode::landed, t);
        changed_ = true;
      }
      break;
    case Mode::hovering:
      if (t >= leave_time(d) - 1e-9) go_home(d, t, "battery");
      break;
    case Mode::held:
      if (t >= leave_time(d) - 1e-9) {
        go_home(d, t, "battery");
        break;
      }
      if (t >= d.hold_until) {  // the hold is over: the task may go to any drone again
        Task& tk = tasks_[static_cast<std::size_t>(d.held_for)];
        if (!tk.flags.same_drone) tk.bound.reset();
        d.held_for = -1;
        set_mode(d, Mode::hovering, t);
        changed_ = true;
      }
      break;
    default:
      break;
  }
}

// Where a dispatch of t's head segment sends d: its fly_to, or where the task's previous fly_to
// went; always at d's own layer.
Vec3 Runtime::dispatch_target(const Drone& d, const Task& t) const {
  const std::size_t h = t.head();
  Vec3 to = t.location;
  if (h < t.actions.size() && t.actions[h].type == ActionType::fly_to) to = t.actions[h].to;
  // Earlier non-flying actions happen where the task's previous fly_to went.
  for (std::size_t i = h; i-- > 0;)
    if (t.actions[i].type == ActionType::fly_to) {
      if (h < t.actions.size() && t.actions[h].type != ActionType::fly_to) to = t.actions[i].to;
      break;
    }
  // Every leg at the drone's own layer: layers separation_m apart keep level flights apart
  // (docs/swath-fleet.md, "Safety envelope"); a fly_to's height was checked, not flown.
  to.z = d.layer_m;
  return to;
}

void Runtime::dispatch(Drone& d, Task& t, double at) {
  t.serving = d.index;
  d.task = t.id;
  if (d.held_for == t.id) d.held_for = -1;
  const std::size_t h = t.head();
  const Vec3 to = dispatch_target(d, t);
  for (std::size_t i = h; i < t.actions.size(); ++i) {
    if (i > h && t.actions[i].type == ActionType::fly_to) break;
    if (t.actions[i].state == ActionState::pending && t.actions[i].type == ActionType::fly_to)
      t.actions[i].state = ActionState::running;
  }
  log(at_json(json{{"ev", "dispatch"}, {"drone", d.index}, {"task", t.id}, {"segment", t.segment}},
              to));
  if (d.mode == Mode::landed) {
    integrate(d, at);
    d.airborne_since = at;
    // Take off: climb at home, then the leg climbs to the layer and flies.
  }
  start_leg(d, to, Mode::flying, at);
}

}  // namespace swath::fleet::rt
