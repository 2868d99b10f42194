// The tick loop (docs/swath-fleet.md) and what it steps: the clock, the drones' events, results
// and delays due, the external vehicles' reports, the run's record.

#include <chrono>

#include "runtime/runtime_impl.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/fleet/simulated_fleet.hpp"

namespace swath::fleet::rt {

Runtime::Runtime(const App& app, const World& world, const std::vector<DroneSpec>& specs,
                 const RuntimeSettings& settings, Backend& backend)
    : app_(app),
      world_(world),
      settings_(settings),
      app_rng_(vehicle::SplitMix64::stream(settings.seed, "app")),
      sched_rng_(vehicle::SplitMix64::stream(settings.seed, "scheduler")),
      backend_(backend) {
  const bool reactive = settings.scheduler == "reactive";
  scheduler_ = make_scheduler(reactive ? "sa" : settings.scheduler);
  if (!scheduler_)
    throw base::InputError("unknown scheduler \"" + settings.scheduler +
                           "\": use sa, reactive, greedy, round-robin or hungarian");
  if (reactive) {  // the paper's baseline: SA without the forecast terms
    settings_.weights.speculative = 0;
    settings_.weights.avoid_mutual = 0;
  } else if (settings.forecaster != "none") {
    forecaster_ = make_forecaster(settings.forecaster, settings.histories, settings.gmf);
    if (!forecaster_)
      throw base::InputError("unknown forecaster \"" + settings.forecaster +
                             "\": use gmf, constant-velocity or none");
  }
  if (backend_.vehicles() != static_cast<int>(specs.size()))
    throw base::InputError("the backend has " + std::to_string(backend_.vehicles()) +
                           " vehicles for a fleet of " + std::to_string(specs.size()) + " drones");
  settings_.layer_step_m = std::max(settings.layer_step_m, settings.envelope.separation_m);
  layer_step_is_separation_ = settings.envelope.separation_m > settings.layer_step_m;
  settings_.disc_m = std::max(settings.disc_m, settings.envelope.separation_m);
  check_envelope(specs);
  // Routes round the fence only where the vehicles follow the way home the runtime gives them:
  // real ones return home straight (RTL, their own failsafe), so they keep straight legs.
  if (!backend_.reports_every_tick()) settings_.envelope.build_routes();
  envelope_ = std::make_shared<const LocalEnvelope>(settings_.envelope);
  for (std::size_t i = 0; i < specs.size(); ++i) {
    Drone d;
    d.spec = specs[i];
    d.index = static_cast<int>(i);
    d.pos = specs[i].home_m;
    d.pos.z = 0;
    d.soc = specs[i].battery.initial_soc;
    d.layer_m = settings_.layer_base_m + settings_.layer_step_m * static_cast<double>(i);
    d.link_up = backend_.report(d.index).link_up;  // a real vehicle: not until first heard
    if (!d.link_up) d.link_back = kInf;
    d.record.name = specs[i].drone.name;
    drones_.push_back(std::move(d));
  }
  faults_ = settings.faults;
  std::stable_sort(faults_.begin(), faults_.end(), [](const FaultEvent& a, const FaultEvent& b) {
    return a.t_s != b.t_s ? a.t_s < b.t_s : a.drone < b.drone;
  });
}

// The fleet must fit the envelope before anything flies: every layer under the ceiling (and the
// fence's height), every home inside the fence. Homes nearer than separation_m are allowed: the
// take-off rule (separation.cpp) then lets one drone climb there at a time.
void Runtime::check_envelope(const std::vector<DroneSpec>& specs) const {
  const LocalEnvelope& e = settings_.envelope;
  const std::string layers =
      layers_refusal(static_cast<int>(specs.size()), settings_.layer_base_m, settings_.layer_step_m,
                     e.ceiling_m, e.fence_max_altitude_m, layer_step_is_separation_);
  if (!layers.empty()) throw base::InputError(layers);
  if (const std::string fence = fence_size_refusal(e); !fence.empty())
    throw base::InputError(fence);
  const auto where = [](const Vec3& p) {
    return "(" + base::fixed_text(p.x, 1) + ", " + base::fixed_text(p.y, 1) + ") m";
  };
  // Real vehicles also carry the world's own fence (its rectangle, uploaded as an inclusion fence
  // by a MAVLink run): one at home outside it would be outside its own fence before it flies. A
  // simulated drone may start outside it (the scheduler serves nothing outside it).
  LocalEnvelope world_fence;
  if (const auto ring = world_.fence(); ring.size() >= 3 && backend_.reports_every_tick())
    world_fence.inclusions.push_back(ring);
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const Vec3& h = specs[i].home_m;
    if (const std::string why = e.refusal_xy(h.x, h.y); !why.empty())
      throw base::InputError(specs[i].drone.name + "'s home " + where(h) + " is " + why);
    if (!world_fence.refusal_xy(h.x, h.y).empty())
      throw base::InputError(specs[i].drone.name + "'s home " + where(h) +
                             " is outside the world's fence, which the vehicles carry: give "
                             "homes inside it (a fleet file's home_m)");
  }
}

void Runtime::log_states() {
  for (Drone& d : drones_) {
    integrate(d, now_);
    log(at_json(json{{"ev", "drone_state"}, {"drone", d.index}}, d.pos,
                json{{"soc", round6(d.soc)}, {"state", mode_name(d.mode, d.link_up)}}));
    d.record.track.push_back({round6(now_), round6(d.pos.x), round6(d.pos.y), round6(d.pos.z)});
  }
}

// What the external vehicles did since the last tick, in drone order: positions, a link lost
// (docs/swath-fleet.md, 'Faults': after the backend's silence rule the drone is unavailable, its
// request requeued and the vehicle's own failsafe takes it home, as for an injected link_loss) or
// up (first heard, or back: buffered results go out; landed, it rejoins), a target reached, home
// reached, a vehicle refusing to fly.
void Runtime::poll_backend() {
  backend_.advance_to(now_);
  for (Drone& d : drones_) {
    const VehicleReport r = backend_.report(d.index);
    if (r.position_known) d.reported = r.position_m;
    integrate(d, now_);
    // A vehicle's own battery report replaces the model's estimate (the model's energy figures
    // stay); the decisions to head home read it from here on.
    if (r.battery_soc >= 0) d.soc = r.battery_soc;
    if (d.mode == Mode::lost) continue;
    if (!r.refusal.empty()) {  // it will not fly: out of the fleet, its work requeued
      log(json{{"ev", "vehicle_refused"}, {"drone", d.index}, {"reason", r.refusal}});
      requeue(d, "vehicle_refused");
      leave_spot(d);
      d.leg.reset();
      d.route.clear();
      // Refused in the air (a target outside the fence): it still goes home and lands; the
      // backend does nothing for a vehicle already down.
      if (d.mode != Mode::landed && d.mode != Mode::charging) backend_.return_home(d.index, now_);
      set_mode(d, Mode::lost, now_);
      changed_ = true;
      continue;
    }
    if (d.link_up && !r.link_up) {
      log(at_json(json{{"ev", "link_lost"}, {"drone", d.index}}, d.pos));
      d.link_up = false;
      d.link_back = kInf;  // until the backend hears it again
      if (d.mode == Mode::flying || d.mode == Mode::positioning || d.mode == Mode::hovering ||
          d.mode == Mode::held) {
        requeue(d, "link_loss");
        go_home(d, now_, "link_loss");
      } else {
        set_mode(d, d.mode, now_);  // acting: it finishes, then goes home (finish_action)
      }
      changed_ = true;
    } else if (!d.link_up && r.link_up) {
      log(at_json(json{{"ev", "link_up"}, {"drone", d.index}}, d.pos));
      d.link_back = now_;
      recover(d, now_);
    }
    if (on_leg(d.mode) && r.arrived && !d.route.empty())
      next_stop(d, now_);
    else if ((d.mode == Mode::flying || d.mode == Mode::positioning) && r.arrived)
      arrive(d, now_);
    else if (d.mode == Mode::returning && r.landed_home)
      land_home(d, now_);
  }
}

// The envelope as the checker reads it (local metres; a fence's rings as [x_m, y_m] pairs).
json Runtime::envelope_json() const {
  const LocalEnvelope& e = settings_.envelope;
  json env{{"ceiling_m", e.ceiling_m}, {"separation_m", e.separation_m}};
  if (std::isfinite(e.fence_max_altitude_m)) env["fence_max_altitude_m"] = e.fence_max_altitude_m;
  const auto rings = [](const std::vector<std::vector<std::array<double, 2>>>& rs) {
    json out = json::array();
    for (const auto& r : rs) {
      json ring = json::array();
      for (const auto& [x, y] : r) ring.push_back(json::array({round6(x), round6(y)}));
      out.push_back(ring);
    }
    return out;
  };
  if (!e.inclusions.empty()) env["inclusions"] = rings(e.inclusions);
  if (!e.exclusions.empty()) env["exclusions"] = rings(e.exclusions);
  return env;
}

// Logs run_start and spawns the app's main, whose body writes into its own promise state.
Task& Runtime::start_main() {
  json drones = json::array();
  for (const Drone& d : drones_)
    drones.push_back(json{{"drone", d.index}, {"name", d.spec.drone.name}, {"soc", round6(d.soc)}});
  json start{{"ev", "run_start"},
             {"app", settings_.app_name},
             {"seed", settings_.seed},
             {"scheduler", settings_.scheduler},
             {"max_time_s", settings_.max_time_s},
             {"drones", drones},
             {"envelope", envelope_json()}};
  if (settings_.origin)
    start["origin"] = {{"lat_deg", settings_.origin->lat_deg},
                       {"lon_deg", settings_.origin->lon_deg}};
  log(start);
  for (Drone& d : drones_) set_mode(d, Mode::landed, 0);
  auto main_state = std::make_shared<detail::State<void>>();
  const App& app = app_;
  spawn(
      -1, Kind{"main"}, Flags{},
      [&app](Ctx& c) -> std::coroutine_handle<> { return app.main(c).release(); }, main_state);
  Task& main = tasks_.front();  // mirror the main body's promise state
  main.result = main_state;
  main.result->task = -1;  // awaiting main is not a sync of the DTG
  auto h = std::coroutine_handle<Co<void>::promise_type>::from_address(main.root.address());
  h.promise().result = main_state;
  return main;
}

// Requests waiting too long for any drone fail visibly (docs/swath-fleet.md).
void Runtime::fail_unserved() {
  for (Task& t : tasks_)
    if (t.has_work() && t.serving < 0 && t.requested &&
        now_ - t.unserved_since_s >= settings_.no_feasible_s) {
      fail_action_futures(t, std::make_exception_ptr(ActionFailed("no_feasible_drone")));
      finish_task(t, TaskStatus::failed, "no_feasible_drone");
    }
}

// The time of the next thing that happens: a drone's event, a result's delivery, a delay's end, a
// fault, a request's no-feasible-drone deadline; infinity when nothing can.
double Runtime::next_happening() const {
  double next = kInf;
  for (const Drone& d : drones_) next = std::min(next, next_event(d));
  for (const Pending& p : pending_) next = std::min(next, p.deliver_s);
  for (const auto& [t, s] : delays_) next = std::min(next, t);
  if (next_fault_ < faults_.size()) next = std::min(next, faults_[next_fault_].t_s);
  next = std::min(next, next_relief_s_);
  next = std::min(next, retry_s_);
  for (const Task& t : tasks_)
    if (t.has_work() && t.serving < 0 && t.requested)
      next = std::min(next, t.unserved_since_s + settings_.no_feasible_s);
  // External vehicles report at any time: every tick (real runs sleep to the next tick;
  // docs/swath-fleet.md, 'The runtime').
  if (backend_.reports_every_tick()) next = std::min(next, now_ + settings_.tick_s);
  return next;
}

// Moves the clock to `next` rounded up to the tick grid, logging drone_state on the way; false
// (with the failure set) past max_time_s.
bool Runtime::advance_clock(double next, std::int64_t& tick_index) {
  const double tick = settings_.tick_s;
  if (next > settings_.max_time_s) next = std::min(next, settings_.max_time_s + tick);
  std::int64_t k = static_cast<std::int64_t>(std::ceil(next / tick - 1e-9));
  k = std::max(k, tick_index + (next > now_ ? 0 : 1));
  if (k <= tick_index) k = tick_index + 1;
  while (next_state_log_ < static_cast<double>(k) * tick - 1e-12) {
    now_ = next_state_log_;
    log_states();
    next_state_log_ += settings_.state_period_s;
  }
  tick_index = k;
  now_ = static_cast<double>(k) * tick;
  if (now_ <= settings_.max_time_s) return true;
  record_.failure = "not completed within max_time_s (" +
                    std::to_string(static_cast<long long>(settings_.max_time_s)) + " s)";
  now_ = settings_.max_time_s;
  return false;
}

// Drones, in (time, drone) order, each through every event up to now.
void Runtime::step_drones_to_now() {
  for (;;) {
    double best = kInf;
    Drone* who = nullptr;
    for (Drone& d : drones_) {
      const double e = next_event(d);
      if (e <= now_ + 1e-12 && e < best) best = e, who = &d;
    }
    if (!who) return;
    step_drone(*who, best);
  }
}

// Faults, results and delays due by now, in (time, drone, sequence) order.
void Runtime::deliver_due() {
  while (next_fault_ < faults_.size() && faults_[next_fault_].t_s <= now_ + 1e-12)
    apply_fault(faults_[next_fault_++]);
  std::stable_sort(pending_.begin(), pending_.end(), [](const Pending& a, const Pending& b) {
    return a.deliver_s != b.deliver_s ? a.deliver_s < b.deliver_s
           : a.drone != b.drone       ? a.drone < b.drone
                                      : a.seq < b.seq;
  });
  std::size_t n = 0;
  while (n < pending_.size() && pending_[n].deliver_s <= now_ + 1e-12) ++n;
  std::vector<Pending> due(pending_.begin(), pending_.begin() + static_cast<long>(n));
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<long>(n));
  for (const Pending& p : due)
    resolve_action(tasks_[static_cast<std::size_t>(p.task)], p.action, p.reading, p.drone);
  for (auto it = delays_.begin(); it != delays_.end();)
    if (it->first <= now_ + 1e-12) {
      wake(*it->second);
      it = delays_.erase(it);
    } else {
      ++it;
    }
}

// The record: outcome, every task ended exactly once (what still runs is cancelled with the
// run), each drone's figures, run_end.
void Runtime::finish_run(const Task& main) {
  record_.completed = main.status == TaskStatus::done;
  if (main.status == TaskStatus::failed && record_.failure.empty())
    record_.failure = "the app's main failed";
  record_.completion_time_s = record_.completed ? main.ended_s : now_;
  record_.end_s = now_;
  for (Task& t : tasks_)
    if (t.status == TaskStatus::running) finish_task(t, TaskStatus::cancelled, "run_ended");
  destroy_frames();
  for (Drone& d : drones_) {
    leave_spot(d);
    integrate(d, now_);
    set_mode(d, d.mode, now_);
    if (!d.span_mode.empty() && now_ > d.span_start)
      d.record.spans.push_back({round6(d.span_start), round6(now_), d.span_mode});
    d.record.distance_m = d.distance_m;
    d.record.flight_s = d.flight_s;
    d.record.idle_s = d.idle_s;
    d.record.energy_wh = d.energy_j / 3600.0;
    d.record.final_soc = d.soc;
    record_.drones.push_back(d.record);
  }
  log(json{{"ev", "run_end"},
           {"completed", record_.completed},
           {"completion_time_s", round6(record_.completion_time_s)}});
}

// The tick loop (docs/swath-fleet.md): take orders from outside, resume what is ready, schedule
// when inputs changed (not while paused), jump to the next thing that happens, let it happen.
// False: an order aborted the run.
bool Runtime::loop(Task& main) {
  std::int64_t tick_index = 0;
  for (;;) {
    if (take_orders()) return false;
    resume_ready();
    destroy_frames();
    if (wall_stalled_) {
      record_.failure = "the app's tasks kept waking each other for more than max_time_s (" +
                        base::shortest_text(settings_.max_time_s) +
                        " s) of wall-clock time without letting the clock move";
      return true;
    }
    if (instant_runaway_) {
      record_.failure = "the app created more than " + std::to_string(kMaxTasksPerInstant) +
                        " tasks at " + base::shortest_text(now_) +
                        " s without letting the clock move (a task that fails at once, retried "
                        "at once?)";
      return true;
    }
    // A signal that came while the app ran (a Python task stopped for it fails the main)
    // is still the run's abort.
    if (main.status != TaskStatus::running) return !(abort_waiting() && take_orders());
    if (!paused_) fail_unserved();
    if (!ready_.empty()) continue;
    if (settings_.relief && !paused_) relieve();
    if (now_ >= retry_s_ - 1e-9) {
      retry_s_ = kInf;
      changed_ = true;
    }
    if (changed_ && !paused_) {
      changed_ = false;
      schedule();
    }
    double next = next_happening();
    // Paused or paced, the clock goes tick by tick: orders are read at every tick.
    if (paused_ || settings_.pace > 0) next = std::min(next, now_ + settings_.tick_s);
    if (!std::isfinite(next)) {
      record_.failure = "the app waits for something that cannot happen (no drone can serve it)";
      return true;
    }
    if (!advance_clock(next, tick_index)) return true;
    if (settings_.pace > 0 && !backend_.reports_every_tick()) wait_for_wall_clock();
    step_drones_to_now();
    if (backend_.reports_every_tick()) poll_backend();
    deliver_due();
  }
}

// The run: the loop, then every vehicle home (or, aborted, told to return or land), the record.
// An exception escaping the loop aborts the run as an order would (settings.on_abort): the
// vehicles are told, the log closed; the record says why.
RunRecord Runtime::run() {
  Task& main = start_main();
  bool ended = true;
  try {
    ended = loop(main);
  } catch (const std::exception& e) {
    abort_run(std::string("exception: ") + e.what(), settings_.on_abort, true);
    ended = false;
  }
  if (ended)
    backend_.end_run();
  else
    backend_.end_abort();
  finish_run(main);
  record_.dtg_json = dtg_json();
  return std::move(record_);
}

}  // namespace swath::fleet::rt

namespace swath::fleet {

vehicle::Drone default_flying_drone() {
  const Kinematics k;
  vehicle::Drone d;
  d.speed_m_s = k.cruise_m_s;
  d.climb_speed_m_s = k.climb_m_s;
  d.descent_speed_m_s = k.descent_m_s;
  d.accel_m_s2 = k.accel_m_s2;
  return d;
}

Kinematics DroneSpec::kinematics() const {
  Kinematics k;
  k.cruise_m_s = drone.speed_m_s.value_or(k.cruise_m_s);
  k.approach_m_s = approach_m_s;
  k.approach_within_m = approach_within_m;
  k.accel_m_s2 = drone.accel_m_s2;
  k.climb_m_s = drone.climb_speed_m_s;
  k.descent_m_s = drone.descent_speed_m_s;
  return k;
}

RunRecord run_app(const App& app, const World& world, const std::vector<DroneSpec>& drones,
                  const RuntimeSettings& settings) {
  if (drones.empty()) throw base::InputError("the fleet has no drones");
  if (settings.backend) {
    rt::Runtime runtime(app, world, drones, settings, *settings.backend);
    return runtime.run();
  }
  SimulatedFleet simulated(drones, settings.layer_base_m,
                           std::max(settings.layer_step_m, settings.envelope.separation_m));
  rt::Runtime runtime(app, world, drones, settings, simulated);
  return runtime.run();
}

}  // namespace swath::fleet
