// Injected faults (docs/swath-fleet.md) as they happen to a drone.

#include "runtime/runtime_impl.hpp"

namespace swath::fleet {

const char* fault_name(FaultKind kind) {
  switch (kind) {
    case FaultKind::link_loss:
      return "link_loss";
    case FaultKind::battery_drop:
      return "battery_drop";
    case FaultKind::motor_failure:
      return "motor_failure";
    case FaultKind::sensor_failure:
      return "sensor_failure";
  }
  return "?";
}

}  // namespace swath::fleet

namespace swath::fleet::rt {

void Runtime::apply_fault(const FaultEvent& f) {
  if (f.drone < 0 || static_cast<std::size_t>(f.drone) >= drones_.size()) return;
  Drone& d = drones_[static_cast<std::size_t>(f.drone)];
  integrate(d, now_);
  json e{{"ev", "fault"}, {"drone", d.index}, {"fault", fault_name(f.kind)}};
  if (f.kind == FaultKind::link_loss || f.kind == FaultKind::sensor_failure)
    e["duration_s"] = round6(f.duration_s);
  e["soc"] = round6(std::max(0.0, d.soc));
  if (f.kind == FaultKind::battery_drop)
    e["to_soc"] = round6(std::max(0.0, std::min(d.soc, f.soc)));
  log(e);
  ++record_.faults_happened;
  if (d.mode == Mode::lost) return;
  switch (f.kind) {
    case FaultKind::link_loss:
      if (!d.link_up) {
        d.link_back = std::max(d.link_back, now_ + f.duration_s);
        break;
      }
      d.link_up = false;
      d.link_back = now_ + f.duration_s;
      if (d.mode == Mode::flying || d.mode == Mode::positioning || d.mode == Mode::hovering ||
          d.mode == Mode::held) {
        requeue(d, "link_loss");
        go_home(d, now_, "link_loss");
      } else {
        set_mode(d, d.mode, now_);  // acting: it finishes, then its failsafe takes it home
      }
      changed_ = true;
      break;
    case FaultKind::battery_drop:
      d.soc = std::min(d.soc, f.soc);
      if (must_go_home(d, now_)) go_home(d, now_, "battery");
      changed_ = true;
      break;
    case FaultKind::motor_failure:
      lose_drone(d, "motor_failure", now_);
      break;
    case FaultKind::sensor_failure:
      d.sensor_ok = false;
      d.sensor_back = std::max(d.sensor_back, now_ + f.duration_s);
      if (d.mode == Mode::acting && d.task >= 0) {
        Task& t = tasks_[static_cast<std::size_t>(d.task)];
        if (t.actions[d.action].type == ActionType::sense) {
          requeue(d, "sensor_failure");
          set_mode(d, Mode::hovering, now_);
        }
      }
      changed_ = true;
      break;
  }
}

// The drone is out of the run where it is (a motor failure; its charge run out): its request
// requeued, a same_drone task bound to it failed (drone_lost), what it finished but could not
// send done again by another.
void Runtime::lose_drone(Drone& d, const std::string& reason, double t) {
  if (d.task >= 0) {
    Task& tk = tasks_[static_cast<std::size_t>(d.task)];
    requeue(d, reason);
    if (tk.flags.same_drone && tk.bound && *tk.bound == d.index) {
      fail_action_futures(tk, std::make_exception_ptr(ActionFailed("drone_lost")));
      finish_task(tk, TaskStatus::failed, "drone_lost");
    }
  }
  for (Task& tk : tasks_)
    if (tk.status == TaskStatus::running && tk.bound && *tk.bound == d.index) {
      if (tk.flags.same_drone) {
        fail_action_futures(tk, std::make_exception_ptr(ActionFailed("drone_lost")));
        finish_task(tk, TaskStatus::failed, "drone_lost");
      } else {
        tk.bound.reset();
      }
    }
  d.held_for = -1;
  leave_spot(d);
  d.leg.reset();
  d.route.clear();
  d.home_retry_s = d.land_retry_s = kInf;
  for (const Pending& p : d.buffered) {
    Action& a = tasks_[static_cast<std::size_t>(p.task)].actions[p.action];
    if (a.state == ActionState::completed) a.state = ActionState::pending;
  }
  d.buffered.clear();
  set_mode(d, Mode::lost, t);
  changed_ = true;
}

// Its charge would run out within a tick at the most it can draw (exhausted_at): it comes down
// where it is, now, and is out of the run, logged (`battery_exhausted`) and counted. Nothing is
// left to fly a cleared landing with; a drone that keeps its reserve never gets here.
void Runtime::exhaust(Drone& d, double t) {
  log(at_json(json{{"ev", "battery_exhausted"}, {"drone", d.index}}, d.pos,
              json{{"soc", round6(std::max(0.0, d.soc))}}));
  ++record_.battery_exhausted;
  backend_.land(d.index, t);
  lose_drone(d, "battery_exhausted", t);
  d.pos.z = 0;
  set_mode(d, Mode::lost, t);  // logs where it came down
}

}  // namespace swath::fleet::rt
