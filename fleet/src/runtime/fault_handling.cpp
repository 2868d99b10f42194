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
  log(json{{"ev", "fault"},
           {"drone", d.index},
           {"fault", fault_name(f.kind)},
           {"duration_s", round6(f.duration_s)},
           {"soc", round6(std::max(0.0, d.soc))}});
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
    case FaultKind::motor_failure: {
      if (d.task >= 0) {
        Task& t = tasks_[static_cast<std::size_t>(d.task)];
        requeue(d, "motor_failure");
        if (t.flags.same_drone && t.bound && *t.bound == d.index) {
          fail_action_futures(t, std::make_exception_ptr(ActionFailed("drone_lost")));
          finish_task(t, TaskStatus::failed, "drone_lost");
        }
      }
      for (Task& t : tasks_)
        if (t.status == TaskStatus::running && t.bound && *t.bound == d.index) {
          if (t.flags.same_drone) {
            fail_action_futures(t, std::make_exception_ptr(ActionFailed("drone_lost")));
            finish_task(t, TaskStatus::failed, "drone_lost");
          } else {
            t.bound.reset();
          }
        }
      d.held_for = -1;
      leave_spot(d);
      d.leg.reset();
      d.route.clear();
      for (const Pending& p : d.buffered) {
        Action& a = tasks_[static_cast<std::size_t>(p.task)].actions[p.action];
        if (a.state == ActionState::completed) a.state = ActionState::pending;
      }
      d.buffered.clear();
      set_mode(d, Mode::lost, now_);
      changed_ = true;
      break;
    }
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

}  // namespace swath::fleet::rt
