#include "swath/energy/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "swath/energy/energy_estimator.hpp"
#include "swath/energy/guidance.hpp"
#include "swath/energy/period_estimate.hpp"
#include "swath/geometry/input_error.hpp"
#include "swath/planning/number_text.hpp"

namespace swath::energy {
namespace {

using geometry::InputError;
using geometry::Point2;
using planning::fixed_text;

constexpr double kGravity = 9.80665;
constexpr double kPi = std::numbers::pi;

std::string point_text(Point2 p) {
  std::string s = "(";
  s += fixed_text(p.x, 1);
  s += ", ";
  s += fixed_text(p.y, 1);
  s += ") m";
  return s;
}

double wrap_pi(double a) {
  while (a > kPi) a -= 2 * kPi;
  while (a < -kPi) a += 2 * kPi;
  return a;
}

struct StepKinematics {
  double ground_speed_mps = 0.0;
  double airspeed_mps = 0.0;
  double lateral_accel_mps2 = 0.0;
  double course_rad = 0.0;  ///< local, counter-clockwise from east
  double path_distance_m = 0.0;
};

// The drone following the stages' fields: position, course and stage are its state.
class Flight {
 public:
  Flight(std::vector<StageField> fields, const SimConfig& config)
      : fields_(std::move(fields)),
        config_(config),
        wind_(wind_velocity(config.wind)),
        position_(config.start) {
    const double bank = config.power.mechanical.max_bank_deg * kPi / 180.0;
    max_lateral_accel_ = kGravity * std::tan(bank);
  }

  bool done() const { return stage_ >= static_cast<int>(fields_.size()); }
  int stage() const { return stage_; }
  Point2 position() const { return position_; }
  double time_s() const { return t_; }
  const std::vector<StageEntry>& entries() const { return entries_; }

  // Switches stages whose triggering point is within reach; true if the stage changed.
  bool trigger() {
    bool changed = false;
    if (entries_.empty()) entries_.push_back({0, t_, position_});
    while (!done()) {
      const Point2 tp = fields_[stage_].trigger;
      if (std::hypot(position_.x - tp.x, position_.y - tp.y) > config_.trigger_radius_m) break;
      ++stage_;
      changed = true;
      best_distance_ = std::numeric_limits<double>::infinity();
      if (!done()) entries_.push_back({stage_, t_, position_});
    }
    return changed;
  }

  StepKinematics step(double dt) {
    StageField& field = fields_[stage_];
    const FieldSample f = guidance_field(field, position_);
    const auto dir = guidance_direction(field, position_);
    if (!dir) {
      std::string msg = field.where;
      msg += ": the guidance field vanishes at ";
      msg += point_text(position_);
      msg +=
          " (grad phi is zero there), so the drone cannot tell where to go; start elsewhere or "
          "check phi";
      throw InputError(msg);
    }
    const double desired = std::atan2(dir->y, dir->x);
    if (!has_course_) {
      course_ = desired;
      has_course_ = true;
    }
    const double speed_guess = std::max(last_ground_speed_, 1.0);
    const double max_turn = max_lateral_accel_ / speed_guess * dt;
    const double turn = std::clamp(wrap_pi(desired - course_), -max_turn, max_turn);
    course_ = wrap_pi(course_ + turn);
    const Point2 u{std::cos(course_), std::sin(course_)};
    const auto cs = course_speed(u, wind_, config_.speed_mps, config_.max_airspeed_mps);
    if (!cs) {
      std::string msg = field.where;
      msg += ": the wind (";
      msg += fixed_text(config_.wind.speed_mps, 1);
      msg += " m/s from ";
      msg += fixed_text(config_.wind.from_bearing_deg, 0);
      msg += " deg) is stronger than the drone's maximum airspeed ";
      msg += fixed_text(config_.max_airspeed_mps, 1);
      msg += " m/s on its course near ";
      msg += point_text(position_);
      throw InputError(msg);
    }
    StepKinematics k;
    k.ground_speed_mps = cs->ground_speed_mps;
    k.airspeed_mps = cs->airspeed_mps;
    k.lateral_accel_mps2 = std::abs(turn) / dt * cs->ground_speed_mps;
    k.course_rad = course_;
    const double g = std::hypot(f.gradient.x, f.gradient.y);
    k.path_distance_m = std::abs(f.phi) / g;
    last_ground_speed_ = cs->ground_speed_mps;
    position_.x += u.x * cs->ground_speed_mps * dt;
    position_.y += u.y * cs->ground_speed_mps * dt;
    t_ += dt;
    check_progress(field);
    return k;
  }

 private:
  void check_progress(const StageField& field) {
    const double d = std::hypot(position_.x - field.trigger.x, position_.y - field.trigger.y);
    if (d < best_distance_) {
      best_distance_ = d;
      best_time_ = t_;
      return;
    }
    if (t_ - best_time_ <= config_.stall_time_s) return;
    std::string msg = field.where;
    msg += ": the drone has not come closer to the triggering point ";
    msg += point_text(field.trigger);
    msg += " for ";
    msg += fixed_text(config_.stall_time_s, 0);
    msg += " s (closest ";
    msg += fixed_text(best_distance_, 1);
    msg += " m at t = ";
    msg += fixed_text(best_time_, 1);
    msg += " s, trigger radius ";
    msg += fixed_text(config_.trigger_radius_m, 1);
    msg += " m); is the triggering point on this stage's path?";
    throw InputError(msg);
  }

  std::vector<StageField> fields_;
  const SimConfig& config_;
  Point2 wind_;
  Point2 position_;
  double t_ = 0.0;
  int stage_ = 0;
  double course_ = 0.0;
  bool has_course_ = false;
  double last_ground_speed_ = 0.0;
  double max_lateral_accel_ = 0.0;
  double best_distance_ = std::numeric_limits<double>::infinity();
  double best_time_ = 0.0;
  std::vector<StageEntry> entries_;
};

// Power the stage's parameters draw on top of the flight (computations and trajectory gains), W.
std::vector<double> stage_parameter_power(const Plan& plan, const SimConfig& config) {
  std::vector<double> out;
  for (const Stage& s : plan.stages) {
    const auto comp = stage_parameters(s.computations, config.computation_parameters);
    const auto traj = stage_parameters(s.trajectory, config.trajectory_parameters);
    double w = computations_power_w(config.power.computations, comp);
    for (std::size_t i = 0; i < traj.size() && i < config.trajectory_gains_w.size(); ++i)
      w += config.trajectory_gains_w[i] * traj[i];
    out.push_back(w);
  }
  return out;
}

// Fixed-width bins of the measured signal, the input of the period estimate.
struct SignalHistory {
  double bin_s;
  std::size_t capacity;
  std::vector<double> bins;
  double sum = 0.0, weight = 0.0, bin_end = 0.0;

  void add(double t, double value) {
    if (t >= bin_end) {
      if (weight > 0.0)
        bins.push_back(sum / weight);
      else if (!bins.empty())
        bins.push_back(bins.back());
      if (bins.size() > capacity) bins.erase(bins.begin(), bins.begin() + (bins.size() - capacity));
      sum = weight = 0.0;
      bin_end = (std::floor(t / bin_s) + 1.0) * bin_s;
    }
    if (std::isfinite(value)) {
      sum += value;
      weight += 1.0;
    }
  }
};

void check_config(const Plan& plan, const SimConfig& config) {
  if (config.power.computations.size() != plan.computations()) {
    std::string msg = config.source;
    msg += ": power.computations lists ";
    msg += std::to_string(config.power.computations.size());
    msg += " computation power curves, the plan ";
    msg += plan.source;
    msg += " has ";
    msg += std::to_string(plan.computations());
    msg += " computations";
    throw InputError(msg);
  }
  if (config.computation_parameters.size() > plan.computations() ||
      config.trajectory_parameters.size() > plan.trajectory_parameters()) {
    std::string msg = config.source;
    msg += ": parameters give more values than the plan ";
    msg += plan.source;
    msg += " has parameters (";
    msg += std::to_string(plan.trajectory_parameters());
    msg += " trajectory, ";
    msg += std::to_string(plan.computations());
    msg += " computations)";
    throw InputError(msg);
  }
}

struct FlownStep {
  double t_s;       ///< at the start of the step
  int stage;        ///< the stage flown during the step
  Point2 end;       ///< position at the end of the step
  int stage_after;  ///< the stage after the triggers at the end of the step
  StepKinematics kinematics;
};

struct PlannedFlight {
  double time_s = 0.0;
  bool done = false;
  std::vector<StageEntry> entries;
  std::vector<FlownStep> steps;
};

// The path is planned: the flight does not depend on the power, so it is flown first. That tells
// when the mission ends and when each stage's parameters change the power.
PlannedFlight planned_flight(const Plan& plan, const SimConfig& config, bool keep_steps) {
  Flight flight(stage_fields(plan, config.trajectory_parameters), config);
  flight.trigger();
  PlannedFlight out;
  if (keep_steps)
    out.steps.reserve(
        static_cast<std::size_t>(std::min(config.max_time_s, 4 * 3600.0) / config.time_step_s + 1));
  while (!flight.done() && flight.time_s() < config.max_time_s) {
    const double t = flight.time_s();
    const int stage = flight.stage();
    const StepKinematics k = flight.step(config.time_step_s);
    flight.trigger();
    if (keep_steps) out.steps.push_back({t, stage, flight.position(), flight.stage(), k});
  }
  out.time_s = flight.time_s();
  out.done = flight.done();
  out.entries = flight.entries();
  return out;
}

}  // namespace

const char* to_string(FlightStatus status) {
  switch (status) {
    case FlightStatus::completed:
      return "completed";
    case FlightStatus::battery_empty:
      return "battery_empty";
    case FlightStatus::time_limit:
      return "time_limit";
  }
  return "";
}

double planned_flight_time_s(const Plan& plan, const SimConfig& config) {
  return planned_flight(plan, config, false).time_s;
}

SimulationResult simulate(const Plan& plan, const SimConfig& config,
                          const std::function<void(double)>& progress) {
  check_config(plan, config);
  const double dt = config.time_step_s;
  const std::vector<double> extra_w = stage_parameter_power(plan, config);

  const PlannedFlight planned = planned_flight(plan, config, true);
  const double planned_time = planned.time_s;
  const std::vector<StageEntry>& planned_entries = planned.entries;
  const int last_stage = static_cast<int>(plan.stages.size()) - 1;

  SimulationResult result;
  result.planned_time_s = planned_time;
  result.first_period_s = config.initial_period_s;
  GaussianNoise noise(config.power.seed, config.power.noise_w);
  const Battery& battery = config.battery;
  const FourierModel model = fourier_model(config.fourier_order, config.initial_period_s, dt);
  std::optional<EnergyEstimator> estimator;
  SignalHistory history{
      config.initial_period_s / 100.0, static_cast<std::size_t>(1200), {}, 0.0, 0.0, 0.0};
  double next_period_check = config.initial_period_s;

  double soc = battery.initial_soc;
  double energy = 0.0;
  double next_output = 0.0;
  double next_progress = 0.0;
  std::vector<std::pair<double, double>> predictions;  // (t, predicted total)
  int stage_now = 0;

  auto record = [&](const FlownStep& step, double measured, double t) {
    FlightSample s;
    const StepKinematics& k = step.kinematics;
    s.t_s = t;
    s.position = step.end;
    s.stage = std::min(step.stage_after, last_stage);
    s.course_deg = std::fmod(450.0 - k.course_rad * 180.0 / kPi, 360.0);
    s.ground_speed_mps = k.ground_speed_mps;
    s.airspeed_mps = k.airspeed_mps;
    s.path_distance_m = k.path_distance_m;
    s.measured_w = measured;
    s.model_w = estimator->output_w();
    s.soc = soc;
    double rest = estimator->energy_over_j(std::max(0.0, planned_time - t));
    for (std::size_t e = 1; e < planned_entries.size(); ++e) {
      const StageEntry& entry = planned_entries[e];
      if (entry.t_s <= t || entry.stage <= s.stage) continue;
      rest += (extra_w[entry.stage] - extra_w[entry.stage - 1]) * (planned_time - entry.t_s);
    }
    s.predicted_total_j = energy + rest;
    s.coefficients = estimator->state();
    predictions.emplace_back(t, s.predicted_total_j);
    result.samples.push_back(std::move(s));
  };

  result.status = planned.done ? FlightStatus::completed : FlightStatus::time_limit;
  double now = 0.0;
  for (std::size_t i = 0; i < planned.steps.size(); ++i) {
    const FlownStep& step = planned.steps[i];
    const double t = step.t_s;
    const int stage = step.stage;
    const StepKinematics& k = step.kinematics;
    double measured;
    if (!config.replay.t_s.empty()) {
      measured = config.replay.at(t);
    } else {
      measured = mechanical_power_w(config.power.mechanical, k.airspeed_mps, k.lateral_accel_mps2) +
                 config.power.payload_w + extra_w[stage] + noise.next();
    }
    if (!estimator) {
      estimator.emplace(
          model, config.kalman,
          std::isfinite(measured) ? measured : extra_w[stage] + config.power.payload_w);
    } else {
      estimator->predict(stage != stage_now ? extra_w[stage] - extra_w[stage_now] : 0.0);
      estimator->correct(measured);
    }
    stage_now = stage;
    const double power = std::isfinite(measured) ? measured : estimator->output_w();
    energy += power * dt;
    soc = soc_after(battery, soc, power, dt);
    if (!std::isfinite(soc)) soc = 0.0;  // beyond what the battery can deliver
    if (!result.reserve_crossed_s && soc <= battery.reserve_soc) result.reserve_crossed_s = t + dt;

    if (config.estimate_period) {
      history.add(t, measured);
      if (t >= next_period_check) {
        const double period = estimator->model().period_s;
        const auto found =
            estimate_period_s(history.bins, history.bin_s, 0.5 * period, 2.0 * period);
        if (found && std::abs(*found - period) > 0.01 * period) estimator->set_period(*found);
        next_period_check = t + estimator->model().period_s;
      }
    }
    now = t + dt;
    ++result.steps;
    const bool last = i + 1 == planned.steps.size() || soc <= 0.0;
    if (now + 1e-9 >= next_output || last) {
      record(step, measured, now);
      next_output += config.output_interval_s;
    }
    if (progress && now >= next_progress) {
      progress(std::min(1.0, now / std::max(planned_time, dt)));
      next_progress = now + 0.01 * planned_time;
    }
    if (soc <= 0.0) {
      result.status = FlightStatus::battery_empty;
      break;
    }
  }
  result.stages.clear();
  for (const StageEntry& e : planned_entries)
    if (e.t_s <= now) result.stages.push_back(e);
  result.flight_time_s = now;
  result.energy_j = energy;
  result.final_soc = soc;
  result.corrections = estimator ? estimator->corrections() : 0;
  result.final_period_s = estimator ? estimator->model().period_s : config.initial_period_s;
  double sum = 0.0;
  std::size_t count = 0;
  for (const auto& [t, predicted] : predictions) {
    if (t < result.first_period_s || energy <= 0.0) continue;
    const double err = std::abs(predicted - energy) / energy;
    sum += err;
    ++count;
    result.max_relative_error = std::max(result.max_relative_error, err);
  }
  result.mean_relative_error = count > 0 ? sum / static_cast<double>(count) : 0.0;
  if (result.status != FlightStatus::completed) {  // the prediction was for the whole mission
    result.mean_relative_error = result.max_relative_error = std::nan("");
  }
  if (progress) progress(1.0);
  return result;
}

}  // namespace swath::energy
