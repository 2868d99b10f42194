#include "swath/energy/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/energy/energy_estimator.hpp"
#include "swath/energy/guidance.hpp"
#include "swath/energy/period_estimate.hpp"
#include "swath/energy/replanner.hpp"

namespace swath::energy {
namespace {

using base::fixed_text;
using base::InputError;
using geometry::Point2;

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

double gap(Point2 a, Point2 b) {  // std::hypot guards overflow we cannot reach, slowly
  const double dx = a.x - b.x, dy = a.y - b.y;
  return std::sqrt(dx * dx + dy * dy);
}

double wrap_pi(double a) {
  while (a > kPi) a -= 2 * kPi;
  while (a < -kPi) a += 2 * kPi;
  return a;
}

struct StepKinematics {
  double ground_speed_m_s = 0.0;
  double airspeed_m_s = 0.0;
  double lateral_accel_m_s2 = 0.0;
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
  double stage_elapsed_s() const { return entries_.empty() ? 0.0 : t_ - entries_.back().t_s; }

  void set_trajectory_parameters(const std::vector<double>& c) {
    for (StageField& f : fields_) energy::set_trajectory_parameters(f, c);
    best_distance_ = std::numeric_limits<double>::infinity();  // the triggering point moved
  }

  // Switches stages whose triggering point is within reach; true if the stage changed.
  bool trigger() {
    bool changed = false;
    if (entries_.empty()) entries_.push_back({0, t_, position_});
    while (!done()) {
      const Point2 tp = fields_[stage_].trigger;
      if (gap(position_, tp) > config_.trigger_radius_m) break;
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
    const auto cs = course_speed(u, wind_, config_.speed_m_s, config_.max_airspeed_m_s);
    if (!cs) {
      std::string msg = field.where;
      msg += ": the wind (";
      msg += fixed_text(config_.wind.speed_m_s, 1);
      msg += " m/s from ";
      msg += fixed_text(config_.wind.from_bearing_deg, 0);
      msg += " deg) is stronger than the drone's maximum airspeed ";
      msg += fixed_text(config_.max_airspeed_m_s, 1);
      msg += " m/s on its course near ";
      msg += point_text(position_);
      throw InputError(msg);
    }
    StepKinematics k;
    k.ground_speed_m_s = cs->ground_speed_m_s;
    k.airspeed_m_s = cs->airspeed_m_s;
    k.lateral_accel_m_s2 = std::abs(turn) / dt * cs->ground_speed_m_s;
    k.course_rad = course_;
    const double g = std::sqrt(f.gradient.x * f.gradient.x + f.gradient.y * f.gradient.y);
    k.path_distance_m = std::abs(f.phi) / g;
    last_ground_speed_ = cs->ground_speed_m_s;
    position_.x += u.x * cs->ground_speed_m_s * dt;
    position_.y += u.y * cs->ground_speed_m_s * dt;
    t_ += dt;
    check_progress(field);
    return k;
  }

 private:
  void check_progress(const StageField& field) {
    const double d = gap(position_, field.trigger);
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

// The power a stage's parameters add to the flight (computations and trajectory gains), W.
double parameter_power_w(const Stage& stage, const SimConfig& config,
                         const std::vector<double>& trajectory,
                         const std::vector<double>& computations) {
  const auto comp = stage_parameters(stage.computations, computations);
  const auto traj = stage_parameters(stage.trajectory, trajectory);
  double w = computations_power_w(config.power.computations, comp);
  for (std::size_t i = 0; i < traj.size() && i < config.trajectory_gains_w.size(); ++i)
    w += config.trajectory_gains_w[i] * traj[i];
  return w;
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

// The trajectory parameters move along the diagonal of the first stage's box.
std::vector<double> trajectory_at(const Plan& plan, double lambda) {
  std::vector<double> c;
  for (const Interval& b : plan.stages.front().trajectory)
    c.push_back(b.lo + lambda * (b.hi - b.lo));
  return c;
}

// A series kept with bounded memory: every value up to kMaxKeptSamples, then every other one is
// dropped and only every 2nd, 4th, ... new one kept, so memory stays bounded however long the
// flight (the run command streams the full series to its files); the last value is always kept.
template <typename T>
class BoundedSeries {
 public:
  explicit BoundedSeries(std::vector<T>& values) : values_(values) {}
  void add(T v) {
    ++count_;
    if ((count_ - 1) % stride_ != 0) {
      pending_last_ = std::move(v);
      return;
    }
    pending_last_.reset();
    values_.push_back(std::move(v));
    if (values_.size() <= kMaxKeptSamples) return;
    std::size_t j = 0;
    for (std::size_t i = 0; i < values_.size(); i += 2) values_[j++] = std::move(values_[i]);
    values_.resize(j);
    stride_ *= 2;
  }
  /// The last value added (kept or not) ends the series.
  void finish() {
    if (pending_last_) values_.push_back(std::move(*pending_last_));
    pending_last_.reset();
  }
  std::size_t count() const { return count_; }

 private:
  std::vector<T>& values_;
  std::optional<T> pending_last_;
  std::size_t count_ = 0, stride_ = 1;
};

// Each stage's duration when the plan is flown from the start with parameters c: the remaining
// path the trajectory parameters imply.
std::vector<double> stage_durations(const Plan& plan, const SimConfig& config,
                                    const std::vector<double>& c, double* total,
                                    std::vector<Point2>* path = nullptr) {
  Flight flight(stage_fields(plan, c), config);
  flight.trigger();
  std::vector<Point2> unused;
  BoundedSeries<Point2> points(path ? *path : unused);
  if (path) points.add(flight.position());
  double next = config.output_interval_s;
  while (!flight.done() && flight.time_s() < config.max_time_s) {
    flight.step(config.time_step_s);
    flight.trigger();
    if (path && (flight.time_s() + 1e-9 >= next || flight.done())) {
      points.add(flight.position());
      next += config.output_interval_s;
    }
  }
  points.finish();
  std::vector<double> d(plan.stages.size(), 0.0);
  const auto& e = flight.entries();
  for (std::size_t k = 0; k < e.size(); ++k)
    d[e[k].stage] = (k + 1 < e.size() ? e[k + 1].t_s : flight.time_s()) - e[k].t_s;
  if (total) *total = flight.time_s();
  return d;
}

// rows[i] belongs to lambdas[i] (ascending); linear in between, the end rows beyond.
std::vector<double> row_at(const std::vector<double>& lambdas,
                           const std::vector<std::vector<double>>& rows, double lambda) {
  if (lambdas.size() == 1) return rows[0];
  std::size_t i = 1;
  while (i + 1 < lambdas.size() && lambda > lambdas[i]) ++i;
  const double f = std::clamp((lambda - lambdas[i - 1]) / (lambdas[i] - lambdas[i - 1]), 0.0, 1.0);
  std::vector<double> out(rows[0].size());
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k] = rows[i - 1][k] + f * (rows[i][k] - rows[i - 1][k]);
  return out;
}

// Stage durations at a few lambdas, interpolated between them.
struct PathTable {
  std::vector<double> lambdas;                 // ascending
  std::vector<std::vector<double>> durations;  // [lambda][stage]

  std::vector<double> at(double lambda) const { return row_at(lambdas, durations, lambda); }
};

// Remaining seconds in each stage from `stage`, `elapsed` seconds into it.
std::vector<double> remaining_by_stage(const std::vector<double>& durations, int stage,
                                       double elapsed) {
  std::vector<double> r(durations.size(), 0.0);
  for (std::size_t k = static_cast<std::size_t>(stage); k < durations.size(); ++k)
    r[k] = durations[k];
  if (stage < static_cast<int>(r.size())) r[stage] = std::max(0.0, r[stage] - elapsed);
  return r;
}

// Stages with the same bounds draw the same parameter power for a choice.
std::vector<int> bound_groups(const Plan& plan, std::vector<int>* representative) {
  std::vector<int> group(plan.stages.size());
  for (std::size_t k = 0; k < plan.stages.size(); ++k) {
    const Stage& s = plan.stages[k];
    group[k] = -1;
    for (std::size_t g = 0; g < representative->size(); ++g) {
      const Stage& r = plan.stages[(*representative)[g]];
      if (r.trajectory == s.trajectory && r.computations == s.computations)
        group[k] = static_cast<int>(g);
    }
    if (group[k] < 0) {
      group[k] = static_cast<int>(representative->size());
      representative->push_back(static_cast<int>(k));
    }
  }
  return group;
}

// The remaining time of the mission from a point of it, in total and per group of stages, at
// each lambda of the path table; linear in between (as the table is).
struct RestTable {
  std::vector<double> lambdas;
  std::vector<std::vector<double>> rows;  // [lambda]: total, then per group

  RestTable(const PathTable& table, const std::vector<int>& group, std::size_t groups_count,
            int stage, double elapsed)
      : lambdas(table.lambdas) {
    for (const auto& d : table.durations) {
      const std::vector<double> r = remaining_by_stage(d, stage, elapsed);
      std::vector<double> row(groups_count + 1, 0.0);
      for (std::size_t k = 0; k < r.size(); ++k) {
        row[0] += r[k];
        row[group[k] + 1] += r[k];
      }
      rows.push_back(std::move(row));
    }
  }

  // [total, per group...] at lambda.
  std::vector<double> at(double lambda) const { return row_at(lambdas, rows, lambda); }
};

}  // namespace

SimulationResult simulate(const Plan& plan, const SimConfig& config,
                          const std::function<void(double)>& progress, const SampleSink& sink) {
  check_config(plan, config);
  const double dt = config.time_step_s;
  const Stage& first = plan.stages.front();
  bool trajectory_free = false;
  for (const Interval& b : first.trajectory) trajectory_free = trajectory_free || b.hi > b.lo;
  trajectory_free = trajectory_free && config.replan;
  bool computations_free = false;
  for (const Stage& st : plan.stages)
    for (const Interval& b : st.computations) computations_free = computations_free || b.hi > b.lo;
  const bool replanning = config.replan && (trajectory_free || computations_free);

  // Initial parameters: the config's, else the upper bounds.
  std::vector<double> traj = stage_parameters(first.trajectory, config.trajectory_parameters);
  std::vector<double> comps = config.computation_parameters;
  for (std::size_t j = comps.size(); j < plan.computations(); ++j) {
    double hi = 0.0;
    for (const Stage& st : plan.stages) hi = std::max(hi, st.computations[j].hi);
    comps.push_back(hi);
  }
  double lambda = 1.0;
  if (trajectory_free && !first.trajectory.empty()) {
    const Interval& b = first.trajectory[0];
    lambda = b.hi > b.lo ? std::clamp((traj[0] - b.lo) / (b.hi - b.lo), 0.0, 1.0) : 1.0;
    traj = trajectory_at(plan, lambda);
  }

  PathTable table;
  double planned_time = 0.0;
  SimulationResult result;
  if (trajectory_free) {
    for (int i = 0; i <= 4; ++i) {
      table.lambdas.push_back(i / 4.0);
      double total = 0.0;
      const bool initial = std::abs(i / 4.0 - lambda) < 1e-12;
      table.durations.push_back(stage_durations(plan, config, trajectory_at(plan, i / 4.0), &total,
                                                initial ? &result.planned_path : nullptr));
    }
    if (result.planned_path.empty()) {
      double total = 0.0;
      stage_durations(plan, config, traj, &total, &result.planned_path);
    }
    for (double d : table.at(lambda)) planned_time += d;
  } else {
    table.lambdas.push_back(lambda);
    table.durations.push_back(
        stage_durations(plan, config, traj, &planned_time, &result.planned_path));
  }
  for (const StageField& f : stage_fields(plan, traj)) result.planned_triggers.push_back(f.trigger);

  result.planned_time_s = planned_time;
  result.first_period_s = config.initial_period_s;
  Flight flight(stage_fields(plan, traj), config);
  flight.trigger();
  GaussianNoise noise(config.power.seed, config.power.noise_w);
  const Battery& battery = config.battery;
  std::optional<EnergyEstimator> estimator;
  SignalHistory history{config.initial_period_s / 100.0, 1200, {}, 0.0, 0.0, 0.0};
  double next_period_check = config.initial_period_s;
  const int last_stage = static_cast<int>(plan.stages.size()) - 1;

  double soc = battery.initial_soc;
  double energy = 0.0, next_output = 0.0, next_progress = 0.0, next_replan = 0.0;
  double last_raise = -1e300;
  BoundedSeries<FlightSample> kept(result.samples);
  double last_recorded_t_s = -INFINITY;
  std::vector<double> traj_sum(traj.size(), 0.0), comp_sum(comps.size(), 0.0);
  result.control.push_back({0.0, traj, comps, true});
  double power_now = parameter_power_w(plan.stages[flight.stage()], config, traj, comps);

  // Energy of the rest of the mission for a choice: the model's integral over the remaining time
  // plus, stage by stage, how much the choice's parameter power differs from what the model has
  // now. The same prediction drives the replanner and is written to energy.csv.
  std::vector<int> representative;
  const std::vector<int> group = bound_groups(plan, &representative);
  double measured_sum = 0.0, measured_count = 0.0;
  double pending_lambda = -1.0;  // >= 0: a trajectory change waiting for the next stage
  int stage_seen = flight.stage();
  auto rest_table = [&] {
    return RestTable(table, group, representative.size(), flight.stage(), flight.stage_elapsed_s());
  };
  auto rest_energy = [&](const RestTable& rt, double l, const std::vector<double>& t_params,
                         const std::vector<double>& c_params) {
    const std::vector<double> row = rt.at(l);
    const double total = row[0];
    double shift = 0.0;
    for (std::size_t g = 0; g + 1 < row.size(); ++g)
      if (row[g + 1] > 0.0)
        shift += (parameter_power_w(plan.stages[representative[g]], config, t_params, c_params) -
                  power_now) *
                 row[g + 1];
    // Within the first period the model has not yet told its mean from its harmonics: the mean
    // measured power so far predicts better.
    const double base = flight.time_s() < config.initial_period_s && measured_count > 0
                            ? measured_sum / measured_count * total
                            : estimator->energy_over_j(total);
    return std::pair{base + shift, total};
  };

  auto record = [&](const StepKinematics& k, double measured) {
    FlightSample s;
    s.t_s = flight.time_s();
    s.position = flight.position();
    s.stage = std::min(flight.stage(), last_stage);
    s.course_deg = std::fmod(450.0 - k.course_rad * 180.0 / kPi, 360.0);
    s.ground_speed_m_s = k.ground_speed_m_s;
    s.airspeed_m_s = k.airspeed_m_s;
    s.path_distance_m = k.path_distance_m;
    s.measured_w = measured;
    s.model_w = estimator->output_w();
    s.soc = soc;
    s.predicted_total_j =
        energy + (flight.done() ? 0.0 : rest_energy(rest_table(), lambda, traj, comps).first);
    s.coefficients = estimator->state();
    if (sink) sink(s);
    last_recorded_t_s = s.t_s;
    kept.add(std::move(s));
  };

  result.status = FlightStatus::completed;
  int cached_stage = -1;
  long params_version = 0, cached_version = 0;
  double stage_power = power_now;
  std::vector<double> flown_traj, flown_comp;
  StepKinematics k{};
  double measured = 0.0;
  while (!flight.done()) {
    if (flight.time_s() >= config.max_time_s) {
      result.status = FlightStatus::time_limit;
      break;
    }
    const double t = flight.time_s();
    const int stage = flight.stage();
    double step_w = 0.0;  // a change of the parameter power, for the model's input (eq. 8)
    if (stage != stage_seen) {
      stage_seen = stage;
      // Trajectory parameters change where a stage begins: changed mid-stage they would move
      // the curve under the drone and make it detour.
      if (pending_lambda >= 0.0) {
        lambda = pending_lambda;
        pending_lambda = -1.0;
        traj = trajectory_at(plan, lambda);
        flight.set_trajectory_parameters(traj);
        result.control.push_back({t, traj, comps, result.control.back().feasible});
        ++params_version;
      }
    }
    if (stage != cached_stage || params_version != cached_version) {
      cached_stage = stage;
      cached_version = params_version;
      stage_power = parameter_power_w(plan.stages[stage], config, traj, comps);
      flown_traj = stage_parameters(plan.stages[stage].trajectory, traj);
      flown_comp = stage_parameters(plan.stages[stage].computations, comps);
    }
    if (stage_power != power_now) {
      step_w = stage_power - power_now;
      power_now = stage_power;
    }
    if (replanning && estimator && t + 1e-9 >= next_replan) {
      next_replan = t + config.mpc_period_s;
      ReplanProblem problem;
      problem.computation_bounds = plan.stages[stage].computations;
      problem.quality_weights = config.quality_weights;
      problem.trajectory_free = trajectory_free;
      problem.battery = battery;
      problem.soc = soc;
      problem.margin = config.mpc_margin;
      const RestTable rt = rest_table();
      problem.rest_energy_j = [&](double l, const std::vector<double>& c) {
        return rest_energy(rt, l, trajectory_free ? trajectory_at(plan, l) : traj, c).first;
      };
      problem.rest_time_s = [&](double l) { return rt.at(l)[0]; };
      ReplanChoice choice = choose_parameters(problem);
      ++result.replans;
      if (!choice.feasible) ++result.infeasible_replans;
      const double q_old = computation_quality(problem.computation_bounds, config.quality_weights,
                                               stage_parameters(problem.computation_bounds, comps));
      const double q_new = computation_quality(problem.computation_bounds, config.quality_weights,
                                               choice.computations);
      const double planned_lambda = pending_lambda >= 0.0 ? pending_lambda : lambda;
      const bool raises =
          q_new > q_old + 1e-12 || (trajectory_free && choice.lambda > planned_lambda + 1e-9);
      const bool changes =
          choice.computations != stage_parameters(problem.computation_bounds, comps) ||
          (trajectory_free && std::abs(choice.lambda - planned_lambda) > 1e-9);
      if (changes && (!raises || t - last_raise >= config.mpc_horizon_s)) {
        if (raises) last_raise = t;
        // Keep the levels of computations the stage switches off (bounds [0, 0]) for later.
        const std::vector<double> before = comps;
        for (std::size_t j = 0; j < comps.size(); ++j)
          if (problem.computation_bounds[j].hi > problem.computation_bounds[j].lo)
            comps[j] = choice.computations[j];
        pending_lambda =
            trajectory_free && std::abs(choice.lambda - lambda) > 1e-9 ? choice.lambda : -1.0;
        if (comps != before) result.control.push_back({t, traj, comps, choice.feasible});
        ++params_version;
        stage_power = parameter_power_w(plan.stages[stage], config, traj, comps);
        flown_traj = stage_parameters(plan.stages[stage].trajectory, traj);
        flown_comp = stage_parameters(plan.stages[stage].computations, comps);
        cached_version = params_version;
        step_w += stage_power - power_now;
        power_now = stage_power;
      } else if (!choice.feasible && result.control.back().feasible) {
        result.control.push_back({t, traj, comps, false});
      }
    }
    k = flight.step(dt);
    if (!config.replay.t_s.empty()) {
      measured = config.replay.at(t);
    } else {
      measured = mechanical_power_w(config.power.mechanical, k.airspeed_m_s, k.lateral_accel_m_s2) +
                 config.power.payload_w + power_now + noise.next();
    }
    if (!estimator) {
      estimator.emplace(fourier_model(config.fourier_order, config.initial_period_s, dt),
                        config.kalman,
                        std::isfinite(measured) ? measured : power_now + config.power.payload_w);
    } else {
      estimator->predict(step_w);
      estimator->correct(measured);
    }
    const double power = std::isfinite(measured) ? measured : estimator->output_w();
    if (std::isfinite(measured)) {
      measured_sum += measured;
      measured_count += 1.0;
    }
    energy += power * dt;
    soc = soc_after(battery, soc, power, dt);
    if (!std::isfinite(soc)) soc = 0.0;  // beyond what the battery can deliver
    if (!result.reserve_crossed_s && soc <= battery.reserve_soc) result.reserve_crossed_s = t + dt;
    for (std::size_t i = 0; i < traj_sum.size() && i < flown_traj.size(); ++i)
      traj_sum[i] += flown_traj[i] * dt;
    for (std::size_t j = 0; j < comp_sum.size(); ++j) comp_sum[j] += flown_comp[j] * dt;

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
    flight.trigger();
    ++result.steps;
    const double now = flight.time_s();
    if (now + 1e-9 >= next_output || flight.done() || soc <= 0.0) {
      record(k, measured);
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
  if (estimator && last_recorded_t_s < flight.time_s()) record(k, measured);
  kept.finish();
  result.stages = flight.entries();
  result.flight_time_s = flight.time_s();
  result.energy_j = energy;
  result.final_soc = soc;
  result.mean_power_w = result.flight_time_s > 0 ? energy / result.flight_time_s : 0.0;
  result.corrections = estimator ? estimator->corrections() : 0;
  result.final_period_s = estimator ? estimator->model().period_s : config.initial_period_s;
  for (double v : traj_sum)
    result.mean_trajectory.push_back(v / std::max(result.flight_time_s, dt));
  for (double v : comp_sum)
    result.mean_computations.push_back(v / std::max(result.flight_time_s, dt));
  double sum = 0.0;
  std::size_t count = 0;
  for (const FlightSample& sample : result.samples) {  // every sample, or evenly decimated
    if (sample.t_s < result.first_period_s || energy <= 0.0) continue;
    const double err = std::abs(sample.predicted_total_j - energy) / energy;
    sum += err;
    ++count;
    result.max_relative_error = std::max(result.max_relative_error, err);
  }
  result.mean_relative_error = count > 0 ? sum / static_cast<double>(count) : 0.0;
  if (result.status != FlightStatus::completed)  // the prediction was for the whole mission
    result.mean_relative_error = result.max_relative_error = std::nan("");
  if (progress) progress(1.0);
  return result;
}

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

FixedComparison compare_fixed(const Plan& plan, const SimConfig& config) {
  SimConfig fixed = config;
  fixed.replan = false;
  FixedComparison out;
  auto extreme = [&](bool highest) {
    fixed.trajectory_parameters.clear();
    fixed.computation_parameters.clear();
    for (const Interval& b : plan.stages.front().trajectory)
      fixed.trajectory_parameters.push_back(highest ? b.hi : b.lo);
    for (std::size_t j = 0; j < plan.computations(); ++j) {
      double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
      for (const Stage& st : plan.stages) {
        if (st.computations[j].hi <= 0) continue;  // switched off there
        lo = std::min(lo, st.computations[j].lo);
        hi = std::max(hi, st.computations[j].hi);
      }
      fixed.computation_parameters.push_back(highest ? hi : (std::isfinite(lo) ? lo : 0.0));
    }
    return simulate(plan, fixed);
  };
  out.highest = extreme(true);
  out.lowest = extreme(false);
  if (out.lowest.mean_power_w > 0)
    out.minutes_per_hour = 60.0 * (out.highest.mean_power_w / out.lowest.mean_power_w - 1.0);
  return out;
}

}  // namespace swath::energy
