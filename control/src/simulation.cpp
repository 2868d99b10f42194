#include "swath/control/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <memory>
#include <numbers>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/control/driver.hpp"
#include "swath/control/reactive_scheduler.hpp"
#include "swath/control/rotor_layout.hpp"
#include "swath/control/scheduler.hpp"
#include "swath/control/voltage_compensation.hpp"

namespace swath::control {
namespace {

using base::InputError;
using geometry::Point2;
using vehicle::kNanosecondsPerSecond;
using vehicle::seconds;

constexpr double kDeg = 180.0 / std::numbers::pi;
constexpr SimTime kMetricsPeriod_ns = 1'000'000;  // metrics every 1 ms
constexpr double kLostTrack_m = 50.0;             // 50 m off track for 5 s: lost
constexpr SimTime kLostTrackFor_ns = 5 * kNanosecondsPerSecond;
constexpr double kSettle_m = 1.0;  // "completed": within 1 m of the last point ...
constexpr SimTime kSettleMax_ns = 10 * kNanosecondsPerSecond;  // ... or 10 s after the carrot

// Roll (right wing down), pitch (nose up) and compass yaw of a body FLU → world ENU attitude, deg.
Vec3 euler_deg(const Quat& q) {
  const Vec3 x = vehicle::rotate(q, {1, 0, 0}), y = vehicle::rotate(q, {0, 1, 0}),
             z = vehicle::rotate(q, {0, 0, 1});
  const double roll = std::atan2(y.z, z.z) * kDeg;
  const double pitch = std::asin(std::clamp(x.z, -1.0, 1.0)) * kDeg;
  double yaw = 90.0 - std::atan2(x.y, x.x) * kDeg;
  yaw = std::fmod(yaw + 360.0, 360.0);
  return {roll, pitch, yaw};
}

double wrap_deg(double a) {
  a = std::fmod(a + 180.0, 360.0);
  if (a < 0) a += 360.0;
  return a - 180.0;
}

double tilt_deg(const Quat& q) {
  return std::acos(std::clamp(vehicle::rotate(q, {0, 0, 1}).z, -1.0, 1.0)) * kDeg;
}

double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double l2 = dot(d, d);
  const double t = l2 > 0 ? std::clamp(dot(p - a, d) / l2, 0.0, 1.0) : 0.0;
  return norm(p - (a + t * d));
}

// ---- Preflight: what cannot fly is refused before anything is simulated. ----

ControlTaskConfig task_config(const SimulationSettings& s) {
  ControlTaskConfig c;
  c.gains = s.control.controller;
  // A carrot faster than the velocity limit would run away from the vehicle.
  c.gains.limits.max_speed_m_s = std::max(c.gains.limits.max_speed_m_s, s.speed_m_s + 1.0);
  c.estimator = with_sensor_noise(s.control.estimator, s.physics.sensors);
  c.estimator.gravity_m_s2 = s.environment.gravity_m_s2;
  const vehicle::Airframe& a = s.physics.airframe;
  c.airframe.mass_kg = a.frame.mass_kg;
  c.airframe.inertia_kg_m2 = a.frame.inertia_kg_m2;
  c.airframe.gravity_m_s2 = s.environment.gravity_m_s2;
  c.airframe.rotors = layout_of(a, s.physics.esc);
  c.nominal_rate_hz = s.scheduler.rate_hz;
  return c;
}

void check_lift(const SimulationSettings& s) {
  const vehicle::Airframe& a = s.physics.airframe;
  double lift = 0;
  for (const vehicle::Rotor& r : a.rotors)
    lift += r.efficiency * a.propulsion.thrust_coeff_n_s2 * a.propulsion.max_speed_rad_s *
            a.propulsion.max_speed_rad_s;
  const double weight = a.frame.mass_kg * s.environment.gravity_m_s2;
  if (lift < 1.2 * weight)
    throw InputError("vehicle " + a.name + ": its rotors lift at most " +
                     base::fixed_text(lift, 1) + " N, less than 1.2 times its weight (" +
                     base::fixed_text(1.2 * weight, 1) + " N): it could not be controlled");
}

// The control graph's input a sensor feeds (scheduler.hpp).
GraphInput graph_input(vehicle::SensorType type) {
  switch (type) {
    case vehicle::SensorType::gyro:
      return GraphInput::gyro;
    case vehicle::SensorType::accel:
      return GraphInput::accel;
    case vehicle::SensorType::mag:
      return GraphInput::mag;
    case vehicle::SensorType::baro:
      return GraphInput::baro;
    case vehicle::SensorType::position:
      return GraphInput::position;
  }
  return GraphInput::gyro;
}

std::unique_ptr<Scheduler> make_scheduler(const SchedulerConfig& config,
                                          const vehicle::VehiclePhysics& physics) {
  if (config.mode == SchedulerMode::reactive) {
    std::vector<TriggerSensor> sensors;
    for (std::size_t k = 0; k < physics.sensors.size(); ++k)
      if (physics.sensors[k].trigger)
        sensors.push_back({physics.sensors[k].name, k, physics.sensors[k].period_ns,
                           graph_input(physics.sensors[k].type)});
    if (sensors.empty())
      throw InputError("scheduler: mode reactive needs a sensor with trigger: true in vehicle " +
                       physics.airframe.name);
    if (config.reactive.boot_s >= config.run.max_time_s)
      throw InputError("scheduler: reactive.boot_s " + base::shortest_text(config.reactive.boot_s) +
                       " is not below run.max_time_s " +
                       base::shortest_text(config.run.max_time_s));
    return std::make_unique<ReactiveScheduler>(config.reactive, std::move(sensors), config.rate_hz);
  }
  auto tt = TimeTriggeredScheduler::at_rate(config.rate_hz);
  if (!tt)
    throw InputError("scheduler: rate_hz " + base::shortest_text(config.rate_hz) +
                     " does not give a whole number of nanoseconds per period");
  return std::make_unique<TimeTriggeredScheduler>(*tt);
}

// ---- The battery: paper 004 eq. 12 per metrics step, or with voltage sag (cells > 0). ----

class BatteryState {
 public:
  explicit BatteryState(const energy::Battery& b) : battery_(b), soc_(b.initial_soc) {}
  /// `energy_j` drawn over `dt_s`; false when the battery cannot deliver that power.
  bool draw(double energy_j, double dt_s) {
    if (dt_s <= 0) return true;
    const double power = energy_j / dt_s;
    const double current = current_a(power);
    if (!std::isfinite(current)) return false;
    if (sags()) {
      // What the terminals deliver, V I with V = OCV − I R, must be the power drawn.
      voltage_v_ = vehicle::terminal_voltage_v(battery_, soc_, current);
      delivered_j_ += voltage_v_ * current * dt_s;
    } else {
      // What the cell delivers to the load, V I − R I², is V~ P / V by eq. 12.
      delivered_j_ += (battery_.voltage_v * current - battery_.resistance_ohm * current * current) *
                      dt_s * battery_.voltage_v / battery_.stabilised_voltage_v;
    }
    soc_ = vehicle::soc_after_charge(battery_, soc_, current * dt_s);
    drawn_j_ += energy_j;
    return soc_ > 0;
  }
  /// The current `power_w` would draw now, A (NaN beyond what the battery can deliver).
  double current_a(double power_w) const {
    return sags() ? vehicle::sag_current_a(battery_, soc_, power_w)
                  : energy::battery_current_a(battery_, power_w);
  }
  bool sags() const { return battery_.cells > 0; }
  /// The terminal voltage at the last draw (sag only), V.
  double voltage_v() const { return voltage_v_; }
  void set_voltage_v(double v) { voltage_v_ = v; }
  double soc() const { return soc_; }
  double balance_residual() const {
    return drawn_j_ > 0 ? std::abs(delivered_j_ - drawn_j_) / drawn_j_ : 0.0;
  }

 private:
  energy::Battery battery_;
  double soc_;
  double voltage_v_ = 0;
  double delivered_j_ = 0, drawn_j_ = 0;
};

// ---- Metrics (docs/formats.md, 'Outputs of swath-control and swath-fleet'). ----

class RunningError {
 public:
  void add(double e) {
    sum2_ += e * e;
    max_ = std::max(max_, std::abs(e));
    ++n_;
  }
  ErrorStat stat() const { return {n_ > 0 ? std::sqrt(sum2_ / static_cast<double>(n_)) : 0, max_}; }
  void reset() { *this = {}; }

 private:
  double sum2_ = 0, max_ = 0;
  long n_ = 0;
};

// Latencies in 10 µs bins up to 1 s (bounded memory for any flight length).
class LatencyHistogram {
 public:
  void add(double ms) {
    const auto bin = static_cast<std::size_t>(std::clamp(ms * 100.0, 0.0, 99'999.0));
    ++bins_[bin];
    sum_ += ms;
    max_ = std::max(max_, ms);
    ++n_;
  }
  double mean() const { return n_ > 0 ? sum_ / static_cast<double>(n_) : 0; }
  double max() const { return max_; }
  double quantile(double q) const {
    if (n_ == 0) return 0;
    const auto target = static_cast<std::int64_t>(std::ceil(q * static_cast<double>(n_)));
    std::int64_t seen = 0;
    for (std::size_t k = 0; k < bins_.size(); ++k)
      if ((seen += bins_[k]) >= target) return (static_cast<double>(k) + 1) / 100.0;
    return max_;
  }

 private:
  std::vector<std::int64_t> bins_ = std::vector<std::int64_t>(100'000, 0);
  double sum_ = 0, max_ = 0;
  std::int64_t n_ = 0;
};

double quantile(std::vector<int> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

bool inside(const std::vector<Point2>& ring, Point2 p) {
  bool in = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Point2 a = ring[i], b = ring[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) in = !in;
  }
  return in;
}

double ring_distance(const std::vector<Point2>& ring, Point2 p) {
  double best = INFINITY;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
    best = std::min(best, segment_distance({p.x, p.y, 0}, {ring[i].x, ring[i].y, 0},
                                           {ring[j].x, ring[j].y, 0}));
  return best;
}

// The flown track against a swath plan's area and no-fly zones (docs/swath-plan.md, 'Missions that
// fly as planned').
class PlanCheck {
 public:
  explicit PlanCheck(const FlightMission& m) : mission_(m) {}
  bool active() const { return !mission_.area.empty(); }
  void add(const Vec3& p) {
    const Point2 q{p.x, p.y};
    if (have_last_) {
      const double step = std::hypot(q.x - last_.x, q.y - last_.y);
      const Point2 mid{(q.x + last_.x) / 2, (q.y + last_.y) / 2};
      if (!inside(mission_.area.front(), mid)) outside_m_ += step;
      for (const auto& zone : mission_.no_fly)
        if (inside(zone, mid)) inside_m_ += step;
    }
    for (const auto& zone : mission_.no_fly) {
      const double d = ring_distance(zone, q);
      const double signed_d = inside(zone, q) ? -d : d;
      clearance_ = clearance_ ? std::min(*clearance_, signed_d) : signed_d;
    }
    last_ = q;
    have_last_ = true;
  }
  void write(SimulationSummary& s) const {
    s.checked_against_plan = active();
    s.outside_area_m = outside_m_;
    s.inside_no_fly_m = inside_m_;
    s.min_clearance_m = clearance_;
  }

 private:
  const FlightMission& mission_;
  Point2 last_;
  bool have_last_ = false;
  double outside_m_ = 0, inside_m_ = 0;
  std::optional<double> clearance_;
};

// ---- The flight: the parts on one clock. ----

class Flight {
 public:
  Flight(const SimulationSettings& s, SimulationObserver* observer)
      : s_(s),
        observer_(observer),
        task_(create_task(s)),
        scheduler_(make_scheduler(s.scheduler, s.physics)),
        reactive_(s.scheduler.mode == SchedulerMode::reactive),
        carrot_(s.mission.legs, carrot_limits(s, task_.config())),
        plant_(plant_settings(s, carrot_)),
        computer_(s.control.computer),
        driver_(s.physics.sensors),
        battery_(s.battery),
        compensation_(s.battery, initial_voltage_v(s, battery_)),
        check_(s.mission),
        triggers_(trigger_sensor_names(s.physics)),
        sample_counts_(s.physics.sensors.size(), 0) {
    state_ = task_.initial_state(carrot_.at(0).position_m);
    estimate_deg_ = euler_deg(state_.estimate.attitude);
    setpoint_deg_ = euler_deg(attitude_setpoint_);
    for (const auto& sensor : s.physics.sensors)
      if (sensor.trigger) trigger_index_.push_back(&sensor - s.physics.sensors.data());
    output_period_ns_ = std::max<SimTime>(vehicle::from_seconds(s.scheduler.run.output_interval_s),
                                          kMetricsPeriod_ns) /
                        kMetricsPeriod_ns * kMetricsPeriod_ns;
    max_time_ns_ = vehicle::from_seconds(s.scheduler.run.max_time_s);
    // Metrics from run.metrics_from_s, unless the mission ends before it (then from the start).
    const double from = s.scheduler.run.metrics_from_s;
    metrics_from_ns_ = (!s.loop && vehicle::from_seconds(from) >= carrot_.end_ns())
                           ? 0
                           : vehicle::from_seconds(from);
    summary_.metrics_from_s = seconds(metrics_from_ns_);
    if (reactive_) boot_end_ns_ = vehicle::from_seconds(s.scheduler.reactive.boot_s);
    rate_.triggers.assign(triggers_.size(), 0);
    last_.rotors = task_.config().airframe.rotors.count;
    if (battery_.sags()) {
      battery_.set_voltage_v(compensation_.filtered_voltage_v());
      plant_.set_supply_ratio(battery_.voltage_v() / s.battery.volt_max_v);
    }
  }

  SimulationSummary run() {
    SimTime next_tick = kMetricsPeriod_ns;
    while (!ended_) {
      const SimTime t = std::min({plant_.next_event(), scheduler_->next_release_ns(),
                                  scheduler_->next_refit_ns(), next_tick});
      run_computer_to(t);
      plant_.advance_to(t);
      deliver_samples();
      if (scheduler_->next_refit_ns() == t) computer_.request_refit(scheduler_->begin_refit(t));
      while (scheduler_->next_release_ns() == t)
        computer_.request_control(scheduler_->take_release(), reactive_);
      if (t == next_tick) {
        tick(t);
        next_tick += kMetricsPeriod_ns;
      }
    }
    return finish();
  }

 private:
  static ControlTask create_task(const SimulationSettings& s) {
    check_lift(s);
    auto task = ControlTask::create(task_config(s));
    if (!task)
      throw InputError("vehicle " + s.physics.airframe.name +
                       ": its rotors cannot be mixed (4 to 8 rotors with positive coefficients "
                       "giving rank 4 are needed)");
    return *task;
  }
  static CarrotLimits carrot_limits(const SimulationSettings& s, const ControlTaskConfig& c) {
    const vehicle::Drone drone = s.drone();
    return {drone.speed_m_s.value_or(0.0), drone.climb_speed_m_s, drone.accel_m_s2,
            s.scheduler.run.setpoint_rate_hz, c.gains.limits.yaw_slew_dps * std::numbers::pi / 180};
  }
  static vehicle::FlightModelSettings plant_settings(const SimulationSettings& s,
                                                     const CarrotPath& carrot) {
    vehicle::FlightModelSettings p;
    p.physics = s.physics;
    p.environment = s.environment;
    p.seed = s.seed;
    p.max_step_s = s.scheduler.run.max_step_s;
    p.mission_speed_m_s = s.speed_m_s;
    p.initial.position_m = carrot.at(0).position_m;
    p.initial.rotor_rad_s = vehicle::hover(s.physics.airframe).rotor_rad_s;
    return p;
  }

  // The terminal voltage at take-off: the hover's motors and the avionics drawing.
  static double initial_voltage_v(const SimulationSettings& s, const BatteryState& b) {
    if (!b.sags()) return 0.0;
    const double power = vehicle::hover(s.physics.airframe).motor_power_w + s.physics.avionics_w;
    const double current = b.current_a(power);
    return vehicle::terminal_voltage_v(s.battery, s.battery.initial_soc,
                                       std::isfinite(current) ? current : 0.0);
  }

  // The carrot's latest update at or before t (the 50 Hz stream), its sample time on the
  // simulation's clock.
  Setpoint setpoint_at(SimTime t) const {
    Setpoint sp = carrot_.at(t - lap_start_ns_);
    sp.sampled_ns += lap_start_ns_;
    return sp;
  }

  // The computer's events up to t: an execution reads its inputs when it starts; its pulses
  // reach the ESCs when it ends.
  void run_computer_to(SimTime t) {
    while (const std::optional<ComputerEvent> e = computer_.advance(t)) {
      plant_.advance_to(e->time_ns);
      deliver_samples();
      if (e->type == ComputerEvent::Type::control_start) {
        start_execution(e->time_ns);
      } else if (e->type == ComputerEvent::Type::control_end) {
        end_execution(*e);
      } else {
        scheduler_->end_refit(e->time_ns);
        report_fits(e->time_ns);
      }
    }
  }

  void deliver_samples() {
    for (const vehicle::DeliveredSample& d : plant_.take_samples()) {
      driver_.deliver(d);
      const bool trigger = scheduler_->is_trigger_sensor(d.sensor);
      computer_.sample(trigger);
      if (d.sensor < sample_counts_.size()) ++sample_counts_[d.sensor];
      if (!trigger) continue;
      SensorSample sample;
      sample.time_ns = plant_.now();
      sample.sensor = d.sensor;
      // The trigger reads the filtered value (the driver's) or the converter's raw one.
      const Vec3& v = s_.scheduler.reactive.trigger_signal == TriggerSignal::raw
                          ? d.sample.unfiltered
                          : d.sample.value;
      sample.value = {v.x, v.y, v.z};
      sample.axes = s_.physics.sensors[d.sensor].type == vehicle::SensorType::baro ? 1 : 3;
      if (sample.axes == 1) sample.value[0] = v.z;
      scheduler_->on_sample(sample);
      const bool fired = report_trigger(d.sensor);
      if (s_.scheduler.reactive.oracle && has_snapshot_ && plant_.now() >= boot_end_ns_)
        ask_oracle(d, fired);
    }
  }

  // Whether `sensor`'s sample just now fired (the reactive scheduler's count moved); told to the
  // observer for the raster.
  bool report_trigger(std::size_t sensor) {
    const auto* r = dynamic_cast<const ReactiveScheduler*>(scheduler_.get());
    if (!r) return false;
    for (std::size_t k = 0; k < r->sensors().size(); ++k) {
      if (r->sensors()[k].index != sensor) continue;
      if (seen_triggers_.size() <= k) seen_triggers_.resize(k + 1, 0);
      if (r->stats()[k].triggers == seen_triggers_[k]) return false;
      seen_triggers_[k] = r->stats()[k].triggers;
      if (observer_) observer_->on_trigger(seconds(plant_.now()), k);
      return true;
    }
    return false;
  }

  // The oracle (docs/swath-control.md, simulation only): the control task copied and run on the
  // last execution's snapshot with only this sensor's value replaced; the output changing is the
  // sample's true label. Draws no random numbers, changes no state.
  void ask_oracle(const vehicle::DeliveredSample& d, bool fired) {
    TaskState state = snapshot_state_;
    TaskInput in = snapshot_input_;
    const Vec3& v = d.sample.value;
    EstimatorInput& e = in.sensors;
    switch (s_.physics.sensors[d.sensor].type) {
      case vehicle::SensorType::gyro:
        e.imu.delta_angle_rad = v * e.imu.interval_s;
        break;
      case vehicle::SensorType::accel:
        e.imu.delta_velocity_m_s = v * e.imu.interval_s;
        break;
      case vehicle::SensorType::mag:
        e.mag = {v, true};
        break;
      case vehicle::SensorType::baro:
        e.baro = {v.z, true};
        break;
      case vehicle::SensorType::position:
        e.fix = {v, d.sample.velocity, true, true};
        break;
    }
    const ExecutionOutput out = task_.execute(state, in);
    bool changed = false;
    for (std::size_t i = 0; i < out.rotor_count; ++i)
      changed = changed || std::abs(out.pwm_us[i] - snapshot_pwm_[i]) >=
                               task_.config().gains.change_threshold_us;
    ++oracle_[(fired ? 2 : 0) + (changed ? 1 : 0)];  // tn, fn, fp, tp
  }

  void report_fits(SimTime t) {
    const auto* r = dynamic_cast<const ReactiveScheduler*>(scheduler_.get());
    if (!r || !observer_) return;
    for (std::size_t k = 0; k < r->stats().size(); ++k) {
      const TriggerStats& st = r->stats()[k];
      observer_->on_fit({seconds(t), r->sensors()[k].name, st.dataset, st.model.beta1,
                         st.model.beta2, st.threshold});
    }
  }

  ExecutionRow execution_row(const ComputerEvent& e) const {
    ExecutionRow row{seconds(e.request_ns),
                     seconds(started_ns_),
                     seconds(e.time_ns),
                     e.cause,
                     "",
                     pending_.changed,
                     false,
                     false,
                     {}};
    row.cycles = charged_cycles_;
    if (const auto* r = dynamic_cast<const ReactiveScheduler*>(scheduler_.get())) {
      const ExecutionRecord& x = r->last_execution();
      row.false_positive = x.false_positive;
      row.false_negative = x.false_negative;
      row.x = x.x;
      row.causes = x.causes;
      for (std::size_t k = 0; k < r->sensors().size(); ++k)
        if (x.trigger_sensors >> k & 1)
          row.sensors += (row.sensors.empty() ? "" : "+") + r->sensors()[k].name;
    }
    return row;
  }

  void start_execution(SimTime t) {
    scheduler_->on_execution_start(t);
    charge_execution();
    TaskInput input;
    input.time_ns = t;
    input.sensors = driver_.take(t);
    const vehicle::MultirotorState& x = plant_.state();
    input.sensors.truth = {x.position_m, x.velocity_m_s, x.attitude, x.rate_rad_s};
    input.setpoint = setpoint_at(t);
    if (s_.scheduler.reactive.oracle) {
      snapshot_state_ = state_;
      snapshot_input_ = input;
      has_snapshot_ = true;
    }
    pending_ = task_.execute(state_, input);
    estimate_deg_ = euler_deg(state_.estimate.attitude);
    if (s_.scheduler.reactive.oracle) snapshot_pwm_ = pending_.pwm_us;
    // The outputs compensated for the battery voltage the controller has measured.
    for (std::size_t i = 0; i < pending_.rotor_count; ++i)
      commanded_pwm_[i] = compensation_.pwm_us(pending_.pwm_us[i], task_.config().airframe.rotors);
    started_ns_ = t;
  }

  // What the execution just started costs the computer: the whole graph as requested, or with
  // partial graph execution only the nodes downstream of what triggered it (scheduler.hpp).
  void charge_execution() {
    const ComputerSettings& cs = s_.control.computer;
    charged_cycles_ = cs.control_cycles + (reactive_ ? cs.dispatch_cycles : 0);
    if (!reactive_ || s_.scheduler.reactive.graph_execution != GraphExecution::partial) return;
    const auto& r = static_cast<const ReactiveScheduler&>(*scheduler_);
    const std::optional<unsigned> inputs = r.running_graph_inputs();
    if (!inputs) return;
    charged_cycles_ = graph_cycles(nodes_to_run(*inputs), cs.control_cycles) + cs.dispatch_cycles;
    computer_.set_running_control_cycles(charged_cycles_);
  }

  void end_execution(const ComputerEvent& e) {
    for (std::size_t i = 0; i < pending_.rotor_count; ++i) plant_.command_pwm(i, commanded_pwm_[i]);
    attitude_setpoint_ = pending_.attitude_setpoint;
    setpoint_deg_ = euler_deg(attitude_setpoint_);
    scheduler_->on_execution_end(e.time_ns, pending_.changed);
    if (observer_) observer_->on_execution(execution_row(e));
    const auto cause = static_cast<std::size_t>(e.cause);
    ++rate_.executions;
    ++rate_.by_cause[cause];
    if (!pending_.changed) ++rate_.unchanged;
    const double latency_ms = seconds(e.time_ns - e.request_ns) * 1e3;
    rate_latency_sum_ms_ += latency_ms;
    recent_ends_.push_back(e.time_ns);
    last_pwm_ = commanded_pwm_;
    if (e.time_ns >= metrics_from_ns_) {
      ++summary_.executions.total;
      ++summary_.executions.by_cause[cause];
      if (!pending_.changed) ++unchanged_;
      latency_.add(latency_ms);
    }
  }

  // Every 1 ms: the battery, the metrics, the end conditions; rows and seconds when due.
  void tick(SimTime t) {
    const double dt = seconds(kMetricsPeriod_ns);
    const double motors = plant_.motor_energy_j(), cpu = computer_.energy_j();
    const double avionics = s_.physics.avionics_w * seconds(t);
    const double drawn = (motors - motors_j_) + (cpu - cpu_j_) + (avionics - avionics_j_);
    motors_j_ = motors;
    cpu_j_ = cpu;
    avionics_j_ = avionics;
    const bool powered = battery_.draw(drawn, dt);
    if (battery_.sags() && powered) {
      compensation_.measure(battery_.voltage_v(), dt);
      plant_.set_supply_ratio(battery_.voltage_v() / s_.battery.volt_max_v);
    }
    const vehicle::MultirotorState& x = plant_.state();
    if (have_position_) summary_.distance_m += norm(x.position_m - last_position_);
    last_position_ = x.position_m;
    have_position_ = true;
    // The carrot where the controller aims at t (advanced from its last update, as the control
    // task does): the metrics and rows measure against it, not against the held sample.
    const Setpoint sp = extrapolated(setpoint_at(t), t);
    // A new leg is a new setpoint (paper 002 §4: setpoints change at waypoints, not mid-leg).
    if (sp.leg != last_leg_) {
      last_leg_ = sp.leg;
      scheduler_->on_setpoint_change(t);
    }
    const double cross = cross_track(x.position_m, sp);
    const double carrot_error = norm(x.position_m - sp.position_m);
    // Commanded: the carrot's velocity or the heading changing; quiet again one second after.
    if (sp.yaw_rate_rad_s != 0 || !(sp.velocity_m_s == last_carrot_velocity_) ||
        sp.leg != quiet_leg_)
      commanded_until_ns_ = t + kNanosecondsPerSecond;
    last_carrot_velocity_ = sp.velocity_m_s;
    quiet_leg_ = sp.leg;
    // Once per tick, for the metrics, the row and the end.
    const double tilt = tilt_deg(x.attitude);
    const Vec3 attitude_deg = euler_deg(x.attitude);
    measure(t, attitude_deg, cross, carrot_error, tilt);
    if (t % output_period_ns_ == 0) record(t, x, attitude_deg, sp, cross);
    if (t % kNanosecondsPerSecond == 0) close_second(t);
    if (check_.active() && t % (20 * kMetricsPeriod_ns) == 0) check_.add(x.position_m);
    decide_end(t, x, sp, carrot_error, tilt, powered);
  }

  double cross_track(const Vec3& p, const Setpoint& sp) const {
    const std::size_t leg = std::min(sp.leg, carrot_.legs() - 1);
    const std::vector<Vec3>& points = carrot_.leg(leg);
    if (points.size() < 2) return norm(p - points.front());
    // Segments near the carrot's: a drone lags its carrot by metres, not by kilometres.
    const std::size_t lo = sp.segment > 50 ? sp.segment - 50 : 0;
    const std::size_t hi = std::min(points.size() - 1, sp.segment + 51);
    double best = INFINITY;
    for (std::size_t k = lo; k < hi; ++k)
      best = std::min(best, segment_distance(p, points[k], points[k + 1]));
    return best;
  }

  void measure(SimTime t, const Vec3& truth, double cross, double carrot_error, double tilt) {
    const Vec3& wanted = setpoint_deg_;
    const Vec3& estimate = estimate_deg_;
    const double er = wrap_deg(wanted.x - truth.x), ep = wrap_deg(wanted.y - truth.y);
    second_attitude_.add(er);
    second_attitude_.add(ep);
    if (t < metrics_from_ns_) return;
    attitude_[0].add(er);
    attitude_[1].add(ep);
    const double ey = wrap_deg(wanted.z - truth.z);
    attitude_[2].add(ey);
    estimated_[0].add(wrap_deg(wanted.x - estimate.x));
    estimated_[1].add(wrap_deg(wanted.y - estimate.y));
    estimated_[2].add(wrap_deg(wanted.z - estimate.z));
    ++measured_samples_;
    if (t >= commanded_until_ns_) {
      ++disturbance_samples_;
      disturbance_[0].add(er);
      disturbance_[1].add(ep);
      disturbance_[2].add(ey);
    }
    cross_.add(cross);
    position_.add(carrot_error);
    summary_.max_tilt_deg = std::max(summary_.max_tilt_deg, tilt);
  }

  void record(SimTime t, const vehicle::MultirotorState& x, const Vec3& attitude_deg,
              const Setpoint& sp, double cross) {
    TimeseriesRow& r = last_;
    const double span = seconds(t - last_row_ns_);
    r.t_s = seconds(t);
    r.position_m = x.position_m;
    r.velocity_m_s = x.velocity_m_s;
    r.attitude_deg = attitude_deg;
    r.setpoint_deg = setpoint_deg_;
    r.estimate_deg = estimate_deg_;
    r.carrot_m = sp.position_m;
    r.cross_track_m = cross;
    r.wind_m_s = plant_.wind_m_s();
    r.pwm_us = last_pwm_;
    r.rotor_rad_s = x.rotor_rad_s;
    r.motors_w = span > 0 ? (motors_j_ - row_motors_j_) / span : plant_.motor_power_w();
    r.cpu_w = span > 0 ? (cpu_j_ - row_cpu_j_) / span : 0;
    r.avionics_w = s_.physics.avionics_w;
    r.soc = battery_.soc();
    while (!recent_ends_.empty() && recent_ends_.front() <= t - kNanosecondsPerSecond)
      recent_ends_.pop_front();
    r.executions_last_s = static_cast<int>(recent_ends_.size());
    row_motors_j_ = motors_j_;
    row_cpu_j_ = cpu_j_;
    last_row_ns_ = t;
    if (observer_) observer_->on_row(r);
  }

  // `whole`: the row covers a whole second (the last, partial one is reported but not counted in
  // the per-second statistics).
  void close_second(SimTime t, bool whole = true) {
    rate_.second = static_cast<int>(t / kNanosecondsPerSecond);
    const ComputerStats& c = computer_.stats();
    rate_.cpu_busy = seconds(c.busy_ns - second_busy_ns_);
    rate_.overruns = c.overruns - second_overruns_;
    rate_.latency_mean_ms = rate_.executions > 0 ? rate_latency_sum_ms_ / rate_.executions : 0;
    rate_.attitude_rms_deg = second_attitude_.stat().rms;
    if (auto* r = dynamic_cast<ReactiveScheduler*>(scheduler_.get()))
      rate_.triggers = r->take_trigger_counts();
    second_busy_ns_ = c.busy_ns;
    second_overruns_ = c.overruns;
    if (whole && t > metrics_from_ns_) per_second_.push_back(rate_.executions);
    if (observer_) {
      observer_->on_second(rate_);
      observer_->on_progress(progress(t));
    }
    rate_ = RateRow{};
    rate_.triggers.assign(triggers_.size(), 0);
    rate_latency_sum_ms_ = 0;
    second_attitude_.reset();
  }

  double progress(SimTime t) const {
    if (s_.loop) {
      const double span = s_.battery.initial_soc - s_.battery.reserve_soc;
      return span > 0 ? std::clamp((s_.battery.initial_soc - battery_.soc()) / span, 0.0, 1.0)
                      : 1.0;
    }
    return std::clamp(static_cast<double>(t) / static_cast<double>(carrot_.end_ns() + 1), 0.0, 1.0);
  }

  void decide_end(SimTime t, const vehicle::MultirotorState& x, const Setpoint& sp,
                  double carrot_error, double tilt, bool powered) {
    off_track_since_ns_ = carrot_error > kLostTrack_m ? std::min(off_track_since_ns_, t) : kNever;
    if (tilt > s_.control.controller.limits.crash_tilt_deg) {
      end(t, FlightStatus::lost_control, "tilt " + base::fixed_text(tilt, 1) + " deg");
    } else if (x.position_m.z < 0) {
      end(t, FlightStatus::lost_control, "below the ground");
    } else if (off_track_since_ns_ != kNever && t - off_track_since_ns_ >= kLostTrackFor_ns) {
      end(t, FlightStatus::lost_control, "more than 50 m off the carrot for 5 s");
    } else if (!powered) {
      end(t, FlightStatus::battery_empty, "");
    } else if (battery_.soc() <= s_.battery.reserve_soc && !summary_.reserve_time_s) {
      summary_.reserve_time_s = seconds(t);
      if (s_.loop) end(t, FlightStatus::reserve_reached, "");
    }
    if (ended_) return;
    const SimTime lap_end = lap_start_ns_ + carrot_.end_ns();
    if (t >= lap_end) {
      if (s_.loop) {
        ++summary_.laps;
        lap_start_ns_ = t;
      } else if (norm(x.position_m - sp.position_m) < kSettle_m || t >= lap_end + kSettleMax_ns) {
        summary_.laps = 1;
        end(t, FlightStatus::completed, "");
      }
    }
    if (!ended_ && t >= max_time_ns_) end(t, FlightStatus::time_limit, "");
  }

  void end(SimTime t, FlightStatus status, std::string reason) {
    ended_ = true;
    summary_.status = status;
    summary_.lost_control_reason = std::move(reason);
    summary_.flight_time_s = seconds(t);
    end_ns_ = t;
  }

  SimulationSummary finish() {
    // The last, partial second is reported too, as the second it belongs to.
    if (end_ns_ % kNanosecondsPerSecond != 0)
      close_second((end_ns_ / kNanosecondsPerSecond + 1) * kNanosecondsPerSecond, false);
    SimulationSummary& s = summary_;
    for (int k = 0; k < 3; ++k) {
      s.attitude_error_deg[k] = attitude_[k].stat();
      s.attitude_error_estimated_deg[k] = estimated_[k].stat();
      s.attitude_error_disturbance_deg[k] = disturbance_[k].stat();
    }
    s.disturbance_share = measured_samples_ > 0 ? static_cast<double>(disturbance_samples_) /
                                                      static_cast<double>(measured_samples_)
                                                : 0.0;
    s.cross_track_m = cross_.stat();
    s.position_error_m = position_.stat();
    auto& e = s.executions;
    if (!per_second_.empty()) {
      double sum = 0;
      int above = 0;
      for (int n : per_second_) {
        sum += n;
        if (n > s_.scheduler.rate_hz) ++above;
      }
      e.per_second_mean = sum / static_cast<double>(per_second_.size());
      e.per_second_p5 = quantile(per_second_, 0.05);
      e.per_second_p95 = quantile(per_second_, 0.95);
      e.per_second_max = *std::max_element(per_second_.begin(), per_second_.end());
      e.share_seconds_above_rate = above / static_cast<double>(per_second_.size());
    }
    e.unchanged_fraction =
        e.total > 0 ? static_cast<double>(unchanged_) / static_cast<double>(e.total) : 0;
    e.latency_mean_ms = latency_.mean();
    e.latency_p95_ms = latency_.quantile(0.95);
    e.latency_max_ms = latency_.max();
    const ComputerStats& c = computer_.stats();
    e.overruns = c.overruns;
    s.reactive = reactive_;
    if (const auto* r = dynamic_cast<const ReactiveScheduler*>(scheduler_.get())) {
      for (std::size_t k = 0; k < r->stats().size(); ++k) {
        const TriggerStats& t = r->stats()[k];
        s.triggers.push_back({r->sensors()[k].name, t.samples, t.triggers, t.refits, t.model.beta1,
                              t.model.beta2, t.threshold, t.dataset});
      }
      const FeedbackStats& f = r->feedback();
      auto share = [](std::int64_t part, std::int64_t whole) {
        return whole > 0 ? static_cast<double>(part) / static_cast<double>(whole) : 0.0;
      };
      s.feedback = {f.false_positives, f.false_negatives, f.multi_cause_excluded,
                    share(f.after_boot_fp, f.after_boot), share(f.steady_fp, f.steady)};
      if (s_.scheduler.reactive.oracle) {
        s.oracle = SimulationSummary::Oracle{oracle_[3], oracle_[2], oracle_[0], oracle_[1]};
      }
    } else {
      for (std::size_t k = 0; k < trigger_index_.size(); ++k)
        s.triggers.push_back({triggers_[k], sample_counts_[trigger_index_[k]], 0, 0, 0, 0, 0, 0});
    }
    const double time = seconds(end_ns_);
    s.cpu_utilisation = time > 0 ? seconds(c.busy_ns) / time : 0;
    s.background_completed = c.background_completed;
    s.background_released = c.background_released;
    s.background_skipped = c.background_skipped;
    if (c.background_completed > 0)
      s.background_latency_mean_ms =
          1e3 * seconds(c.background_latency_sum_ns) / static_cast<double>(c.background_completed);
    s.background_latency_max_ms = 1e3 * seconds(c.background_latency_max_ns);
    s.motors_j = motors_j_;
    s.cpu_j = cpu_j_;
    s.avionics_j = avionics_j_;
    s.total_j = motors_j_ + cpu_j_ + avionics_j_;
    // The control task's own share: its cycles (and the reactive dispatch) at the active power
    // above idle.
    const ComputerSettings& cs = s_.control.computer;
    const std::int64_t cycles = cs.control_cycles + (reactive_ ? cs.dispatch_cycles : 0);
    s.cpu_energy_per_execution_mj =
        1e3 * (cs.active_w - cs.idle_w) * seconds(computer_.duration_ns(cycles));
    s.mean_power_w = time > 0 ? s.total_j / time : 0;
    s.final_soc = battery_.soc();
    s.balance_residual = battery_.balance_residual();
    check_.write(s);
    return s;
  }

  const SimulationSettings& s_;
  SimulationObserver* observer_;
  ControlTask task_;
  std::unique_ptr<Scheduler> scheduler_;
  bool reactive_;
  CarrotPath carrot_;
  vehicle::FlightModel plant_;
  FlightComputer computer_;
  SensorDriver driver_;
  BatteryState battery_;
  ThrustCompensation compensation_;
  PlanCheck check_;
  std::vector<std::string> triggers_;
  std::vector<std::size_t> trigger_index_;
  std::int64_t charged_cycles_ = 0;  // the execution under way's (charge_execution)
  std::vector<std::int64_t> sample_counts_;

  TaskState state_;
  ExecutionOutput pending_;
  Quat attitude_setpoint_;
  // euler_deg of attitude_setpoint_ and of the estimate, kept as they change (at executions), not
  // recomputed at every 1 ms tick.
  Vec3 setpoint_deg_, estimate_deg_;
  std::array<double, vehicle::kMaxRotors> last_pwm_{}, commanded_pwm_{};
  SimTime lap_start_ns_ = 0, metrics_from_ns_ = 0, output_period_ns_ = 0, max_time_ns_ = 0;
  SimTime off_track_since_ns_ = kNever, end_ns_ = 0, last_row_ns_ = 0;
  bool ended_ = false, have_position_ = false;
  std::size_t last_leg_ = 0;
  SimTime started_ns_ = 0;
  std::vector<std::int64_t> seen_triggers_;
  // The oracle's snapshot: the task's state before the last execution, its input, its output.
  TaskState snapshot_state_;
  TaskInput snapshot_input_;
  std::array<double, vehicle::kMaxRotors> snapshot_pwm_{};
  bool has_snapshot_ = false;
  SimTime boot_end_ns_ = 0;
  std::array<std::int64_t, 4>
      oracle_{};  // true negatives, false negatives, false positives, true positives
  Vec3 last_position_;
  double motors_j_ = 0, cpu_j_ = 0, avionics_j_ = 0, row_motors_j_ = 0, row_cpu_j_ = 0;

  SimulationSummary summary_;
  std::array<RunningError, 3> attitude_, estimated_, disturbance_;
  std::int64_t measured_samples_ = 0, disturbance_samples_ = 0;
  SimTime commanded_until_ns_ = 0;  // samples before it follow a commanded change
  Vec3 last_carrot_velocity_;
  std::size_t quiet_leg_ = 0;
  RunningError cross_, position_, second_attitude_;
  LatencyHistogram latency_;
  std::int64_t unchanged_ = 0;
  std::vector<int> per_second_;
  RateRow rate_;
  double rate_latency_sum_ms_ = 0;
  SimTime second_busy_ns_ = 0;
  std::int64_t second_overruns_ = 0;
  std::deque<SimTime> recent_ends_;
  TimeseriesRow last_;
};

}  // namespace

const char* to_string(FlightStatus status) {
  switch (status) {
    case FlightStatus::completed:
      return "completed";
    case FlightStatus::reserve_reached:
      return "reserve_reached";
    case FlightStatus::battery_empty:
      return "battery_empty";
    case FlightStatus::time_limit:
      return "time_limit";
    case FlightStatus::lost_control:
      return "lost_control";
  }
  return "unknown";
}

std::vector<std::string> trigger_sensor_names(const vehicle::VehiclePhysics& physics) {
  std::vector<std::string> names;
  for (const auto& s : physics.sensors)
    if (s.trigger) names.push_back(s.name);
  return names;
}

vehicle::Drone SimulationSettings::drone() const {
  vehicle::Drone d;
  d.name = physics.airframe.name;
  d.speed_m_s = speed_m_s;
  // The controller's vertical limit holds both ways (control_task.cpp clamps |v_z| to it).
  d.climb_speed_m_s = control.controller.limits.max_climb_m_s;
  d.descent_speed_m_s = control.controller.limits.max_climb_m_s;
  d.accel_m_s2 = control.controller.limits.max_accel_m_s2;
  return d;
}

SimulationSummary simulate(const SimulationSettings& settings, SimulationObserver* observer) {
  if (settings.mission.legs.empty())
    throw InputError("mission: nothing to fly (fewer than 2 points)");
  if (!(settings.speed_m_s > 0))
    throw InputError("speed " + base::shortest_text(settings.speed_m_s) + " m/s is not > 0");
  Flight flight(settings, observer);
  return flight.run();
}

}  // namespace swath::control
