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
        wind_(config.wind.velocity_m_s()),
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
      msg += fixed_text(config_.wind.speed_m_s(), 1);
      msg += " m/s from ";
      msg += fixed_text(config_.wind.from_deg(), 0);
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
  // stage_parameters() and computations_power_w() inline, in their order of summation: the
  // replanner asks this thousands of times a replan, and two vectors a call were most of its
  // time (and nearly all of it under AddressSanitizer).
  const auto at = [](const std::vector<Interval>& bounds, const std::vector<double>& values,
                     std::size_t i) {
    return i < values.size() ? std::clamp(values[i], bounds[i].lo, bounds[i].hi) : bounds[i].hi;
  };
  const std::vector<PowerCurve>& curves = config.power.computations;
  double w = 0.0;
  for (std::size_t j = 0; j < curves.size() && j < stage.computations.size(); ++j)
    w += computation_power_w(curves[j], at(stage.computations, computations, j));
  for (std::size_t i = 0; i < stage.trajectory.size() && i < config.trajectory_gains_w.size(); ++i)
    w += config.trajectory_gains_w[i] * at(stage.trajectory, trajectory, i);
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

}  // namespace

std::vector<Point2> guided_path(const Plan& plan, const SimConfig& config) {
  std::vector<Point2> path;
  double total = 0.0;
  stage_durations(plan, config, trajectory_at(plan, 1.0), &total, &path);
  return path;
}

namespace {

// Where lambda falls in a table of rows (rows[i] belongs to lambdas[i], ascending): linear in
// between, the end rows beyond.
struct RowPlace {
  std::size_t i = 0;  // between rows i - 1 and i (0: a table of one row)
  double f = 0.0;

  RowPlace(const std::vector<double>& lambdas, double lambda) {
    if (lambdas.size() == 1) return;
    i = 1;
    while (i + 1 < lambdas.size() && lambda > lambdas[i]) ++i;
    f = std::clamp((lambda - lambdas[i - 1]) / (lambdas[i] - lambdas[i - 1]), 0.0, 1.0);
  }
  double value(const std::vector<std::vector<double>>& rows, std::size_t k) const {
    if (i == 0) return rows[0][k];
    return rows[i - 1][k] + f * (rows[i][k] - rows[i - 1][k]);
  }
};

std::vector<double> row_at(const std::vector<double>& lambdas,
                           const std::vector<std::vector<double>>& rows, double lambda) {
  const RowPlace place(lambdas, lambda);
  std::vector<double> out(rows[0].size());
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = place.value(rows, k);
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
  // Read at a lambda with RowPlace (the replanner asks per candidate; no row is built).
};

// ---- The simulation's parts, each advanced once per time step (simulate() composes them). ----

// The plan's parameters as flown: the trajectory (lambda along the first stage's diagonal) and
// the computation levels; the parameter power of the current stage, and its steps, which are the
// energy model's input (paper 004 eq. 8). Trajectory changes wait for the next stage: changed
// mid-stage they would move the curve under the drone and make it detour.
class Parameters {
 public:
  Parameters(const Plan& plan, const SimConfig& config, bool trajectory_free,
             std::vector<double> trajectory, std::vector<double> computations, double lambda,
             int stage)
      : plan_(plan),
        config_(config),
        trajectory_free_(trajectory_free),
        traj_(std::move(trajectory)),
        comps_(std::move(computations)),
        lambda_(lambda),
        stage_seen_(stage),
        power_now_(parameter_power_w(plan.stages[stage], config, traj_, comps_)),
        traj_sum_(traj_.size(), 0.0),
        comp_sum_(comps_.size(), 0.0) {}

  const std::vector<double>& trajectory() const { return traj_; }
  const std::vector<double>& computations() const { return comps_; }
  double lambda() const { return lambda_; }
  /// The lambda the drone will fly: a pending change, else the current one.
  double planned_lambda() const { return pending_lambda_ >= 0.0 ? pending_lambda_ : lambda_; }
  double power_now() const { return power_now_; }
  /// The parameter power's step in this time step, W.
  double step_w() const { return step_w_; }

  /// Before the step: a new stage takes a pending trajectory change; the stage's power.
  void begin_step(int stage, double t, Flight& flight, std::vector<ControlSample>& control) {
    step_w_ = 0.0;
    if (stage != stage_seen_) {
      stage_seen_ = stage;
      if (pending_lambda_ >= 0.0) {
        lambda_ = pending_lambda_;
        pending_lambda_ = -1.0;
        traj_ = trajectory_at(plan_, lambda_);
        flight.set_trajectory_parameters(traj_);
        control.push_back({t, traj_, comps_, control.back().feasible});
        ++version_;
      }
    }
    if (stage != cached_stage_ || version_ != cached_version_) cache(stage);
    take_stage_power();
  }

  /// A replanner's choice taken: the computations at once (where the stage lets them vary), the
  /// trajectory at the next stage.
  void take(const ReplanChoice& choice, const std::vector<Interval>& computation_bounds, int stage,
            double t, std::vector<ControlSample>& control) {
    const std::vector<double> before = comps_;
    // Keep the levels of computations the stage switches off (bounds [0, 0]) for later.
    for (std::size_t j = 0; j < comps_.size(); ++j)
      if (computation_bounds[j].hi > computation_bounds[j].lo) comps_[j] = choice.computations[j];
    pending_lambda_ =
        trajectory_free_ && std::abs(choice.lambda - lambda_) > 1e-9 ? choice.lambda : -1.0;
    if (comps_ != before) control.push_back({t, traj_, comps_, choice.feasible});
    ++version_;
    cache(stage);
    step_w_ += stage_power_ - power_now_;
    power_now_ = stage_power_;
  }

  /// After the step: the time integrals of the flown levels (their means in the result).
  void accumulate(double dt) {
    for (std::size_t i = 0; i < traj_sum_.size() && i < flown_traj_.size(); ++i)
      traj_sum_[i] += flown_traj_[i] * dt;
    for (std::size_t j = 0; j < comp_sum_.size(); ++j) comp_sum_[j] += flown_comp_[j] * dt;
  }
  std::vector<double> mean_trajectory(double seconds) const { return means(traj_sum_, seconds); }
  std::vector<double> mean_computations(double seconds) const { return means(comp_sum_, seconds); }

 private:
  void cache(int stage) {
    cached_stage_ = stage;
    cached_version_ = version_;
    stage_power_ = parameter_power_w(plan_.stages[stage], config_, traj_, comps_);
    flown_traj_ = stage_parameters(plan_.stages[stage].trajectory, traj_);
    flown_comp_ = stage_parameters(plan_.stages[stage].computations, comps_);
  }
  void take_stage_power() {
    if (stage_power_ != power_now_) {
      step_w_ = stage_power_ - power_now_;
      power_now_ = stage_power_;
    }
  }
  static std::vector<double> means(const std::vector<double>& sums, double seconds) {
    std::vector<double> out;
    for (double v : sums) out.push_back(v / seconds);
    return out;
  }

  const Plan& plan_;
  const SimConfig& config_;
  bool trajectory_free_;
  std::vector<double> traj_, comps_;
  double lambda_;
  double pending_lambda_ = -1.0;  // >= 0: a trajectory change waiting for the next stage
  int stage_seen_;
  int cached_stage_ = -1;
  long version_ = 0, cached_version_ = 0;
  double power_now_, stage_power_ = 0.0, step_w_ = 0.0;
  std::vector<double> flown_traj_, flown_comp_;
  std::vector<double> traj_sum_, comp_sum_;
};

// The power the drone draws in a step: the replayed trace, or the power model of the flight
// (mechanical, with the turn's lateral acceleration) plus payload, parameters and noise.
class PowerMeter {
 public:
  explicit PowerMeter(const SimConfig& config)
      : config_(config), noise_(config.power.seed, config.power.noise_w) {}
  double measure(double t, const StepKinematics& k, double parameter_power_w) {
    if (!config_.replay.t_s.empty()) return config_.replay.at(t);
    return mechanical_power_w(config_.power.mechanical, k.airspeed_m_s, k.lateral_accel_m_s2) +
           config_.power.payload_w + parameter_power_w + noise_.next();
  }

 private:
  const SimConfig& config_;
  GaussianNoise noise_;
};

// The energy model (paper 004 §4): the periodic model's Kalman filter, fed by the measured power
// and the parameter power's steps, its period re-estimated once a period from the measured
// signal; and the mean measured power, which predicts better within the first period.
class EnergyModel {
 public:
  explicit EnergyModel(const SimConfig& config)
      : config_(config),
        history_{config.initial_period_s / 100.0, 1200, {}, 0.0, 0.0, 0.0},
        next_period_check_(config.initial_period_s) {}

  bool started() const { return estimator_.has_value(); }
  const EnergyEstimator& estimator() const { return *estimator_; }

  /// One step's measurement; returns the power the battery gives (the model's output where
  /// the measurement is missing).
  double update(double t, double measured, double step_w, double parameter_power_w) {
    if (!estimator_) {
      estimator_.emplace(
          fourier_model(config_.fourier_order, config_.initial_period_s, config_.time_step_s),
          config_.kalman,
          std::isfinite(measured) ? measured : parameter_power_w + config_.power.payload_w);
    } else {
      estimator_->predict(step_w);
      estimator_->correct(measured);
    }
    const double power = std::isfinite(measured) ? measured : estimator_->output_w();
    if (std::isfinite(measured)) {
      measured_sum_ += measured;
      measured_count_ += 1.0;
    }
    if (config_.estimate_period) estimate_period(t, measured);
    return power;
  }

  /// The energy over the next `horizon_s` at the current power level: the mean measured power
  /// within the first period, the model's integral after.
  double energy_over_j(double t, double horizon_s) const {
    return t < config_.initial_period_s && measured_count_ > 0
               ? measured_sum_ / measured_count_ * horizon_s
               : estimator_->energy_over_j(horizon_s);
  }

 private:
  void estimate_period(double t, double measured) {
    history_.add(t, measured);
    if (t < next_period_check_) return;
    const double period = estimator_->model().period_s;
    const auto found = estimate_period_s(history_.bins, history_.bin_s, 0.5 * period, 2.0 * period);
    if (found && std::abs(*found - period) > 0.01 * period) estimator_->set_period(*found);
    next_period_check_ = t + estimator_->model().period_s;
  }

  const SimConfig& config_;
  std::optional<EnergyEstimator> estimator_;
  SignalHistory history_;
  double next_period_check_;
  double measured_sum_ = 0.0, measured_count_ = 0.0;
};

// Energy of the rest of the mission for a choice: the model's integral over the remaining time
// plus, stage by stage, how much the choice's parameter power differs from what is drawn now.
// The same prediction drives the replanner and is written to energy.csv.
class Outlook {
 public:
  Outlook(const Plan& plan, const SimConfig& config, PathTable table)
      : plan_(plan), config_(config), table_(std::move(table)) {
    group_ = bound_groups(plan, &representative_);
  }

  RestTable rest_from(const Flight& flight) const {
    return RestTable(table_, group_, representative_.size(), flight.stage(),
                     flight.stage_elapsed_s());
  }

  double rest_energy_j(const RestTable& rt, double lambda, const std::vector<double>& trajectory,
                       const std::vector<double>& computations, double power_now_w, double t,
                       const EnergyModel& model) const {
    const RowPlace place(rt.lambdas, lambda);
    double shift = 0.0;
    for (std::size_t g = 0; g + 1 < rt.rows[0].size(); ++g) {
      const double seconds = place.value(rt.rows, g + 1);
      if (seconds > 0.0)
        shift += (parameter_power_w(plan_.stages[representative_[g]], config_, trajectory,
                                    computations) -
                  power_now_w) *
                 seconds;
    }
    return model.energy_over_j(t, place.value(rt.rows, 0)) + shift;
  }

 private:
  const Plan& plan_;
  const SimConfig& config_;
  PathTable table_;
  std::vector<int> representative_, group_;
};

// The replanner (paper 004 §5): every mpc_period_s, the parameters whose predicted energy fits
// the battery above its margin at the highest quality; a raise is held at least mpc_horizon_s.
class Replanner {
 public:
  Replanner(const Plan& plan, const SimConfig& config, bool trajectory_free)
      : plan_(plan), config_(config), trajectory_free_(trajectory_free) {}

  void maybe_replan(double t, int stage, double soc, const Flight& flight, Parameters& params,
                    const Outlook& outlook, const EnergyModel& model, SimulationResult& result) {
    if (t + 1e-9 < next_replan_) return;
    next_replan_ = t + config_.mpc_period_s;
    ReplanProblem problem;
    problem.computation_bounds = plan_.stages[stage].computations;
    problem.quality_weights = config_.quality_weights;
    problem.trajectory_free = trajectory_free_;
    problem.battery = config_.battery;
    problem.soc = soc;
    problem.margin = config_.mpc_margin;
    const RestTable rt = outlook.rest_from(flight);
    problem.rest_energy_j = [&](double l, const std::vector<double>& c) {
      const std::vector<double> traj =
          trajectory_free_ ? trajectory_at(plan_, l) : params.trajectory();
      return outlook.rest_energy_j(rt, l, traj, c, params.power_now(), flight.time_s(), model);
    };
    problem.rest_time_s = [&](double l) { return RowPlace(rt.lambdas, l).value(rt.rows, 0); };
    const ReplanChoice choice = choose_parameters(problem);
    ++result.replans;
    if (!choice.feasible) ++result.infeasible_replans;
    const std::vector<double> current =
        stage_parameters(problem.computation_bounds, params.computations());
    const double q_old =
        computation_quality(problem.computation_bounds, config_.quality_weights, current);
    const double q_new = computation_quality(problem.computation_bounds, config_.quality_weights,
                                             choice.computations);
    const double planned = params.planned_lambda();
    const bool raises =
        q_new > q_old + 1e-12 || (trajectory_free_ && choice.lambda > planned + 1e-9);
    const bool changes = choice.computations != current ||
                         (trajectory_free_ && std::abs(choice.lambda - planned) > 1e-9);
    if (changes && (!raises || t - last_raise_ >= config_.mpc_horizon_s)) {
      if (raises) last_raise_ = t;
      params.take(choice, problem.computation_bounds, stage, t, result.control);
    } else if (!choice.feasible && result.control.back().feasible) {
      result.control.push_back({t, params.trajectory(), params.computations(), false});
    }
  }

 private:
  const Plan& plan_;
  const SimConfig& config_;
  bool trajectory_free_;
  double next_replan_ = 0.0;
  double last_raise_ = -1e300;
};

// The battery's state of charge and the energy drawn (paper 004 eq. 12).
struct Charge {
  double soc = 1.0;
  double energy_j = 0.0;
  void drain(const Battery& battery, double power_w, double dt, double t,
             std::optional<double>& reserve_crossed_s) {
    energy_j += power_w * dt;
    soc = soc_after(battery, soc, power_w, dt);
    if (!std::isfinite(soc)) soc = 0.0;  // beyond what the battery can deliver
    if (!reserve_crossed_s && soc <= battery.reserve_soc) reserve_crossed_s = t + dt;
  }
};

// The samples every output interval (and the last step): streamed to the sink, kept bounded.
class Recorder {
 public:
  Recorder(SimulationResult& result, const SampleSink& sink, int last_stage)
      : kept_(result.samples), sink_(sink), last_stage_(last_stage) {}

  void record(const Flight& flight, const StepKinematics& k, double measured, const Charge& charge,
              const EnergyModel& model, double predicted_total_j) {
    FlightSample s;
    s.t_s = flight.time_s();
    s.position = flight.position();
    s.stage = std::min(flight.stage(), last_stage_);
    s.course_deg = std::fmod(450.0 - k.course_rad * 180.0 / kPi, 360.0);
    s.ground_speed_m_s = k.ground_speed_m_s;
    s.airspeed_m_s = k.airspeed_m_s;
    s.path_distance_m = k.path_distance_m;
    s.measured_w = measured;
    s.model_w = model.estimator().output_w();
    s.soc = charge.soc;
    s.predicted_total_j = predicted_total_j;
    s.coefficients = model.estimator().state();
    if (sink_) sink_(s);
    last_recorded_t_s_ = s.t_s;
    kept_.add(std::move(s));
  }
  double last_recorded_t_s() const { return last_recorded_t_s_; }
  void finish() { kept_.finish(); }

 private:
  BoundedSeries<FlightSample> kept_;
  const SampleSink& sink_;
  int last_stage_;
  double last_recorded_t_s_ = -INFINITY;
};

// Whether any parameter of the plan may vary (the replanner has something to choose).
struct Freedom {
  bool trajectory = false, computations = false;
};

Freedom freedom_of(const Plan& plan, const SimConfig& config) {
  Freedom f;
  for (const Interval& b : plan.stages.front().trajectory)
    f.trajectory = f.trajectory || b.hi > b.lo;
  f.trajectory = f.trajectory && config.replan;
  for (const Stage& st : plan.stages)
    for (const Interval& b : st.computations) f.computations = f.computations || b.hi > b.lo;
  return f;
}

// The parameters at take-off: the config's, else the upper bounds; the trajectory on the first
// stage's diagonal at `lambda`.
struct InitialParameters {
  std::vector<double> trajectory, computations;
  double lambda = 1.0;
};

InitialParameters initial_parameters(const Plan& plan, const SimConfig& config,
                                     bool trajectory_free) {
  const Stage& first = plan.stages.front();
  InitialParameters p;
  p.trajectory = stage_parameters(first.trajectory, config.trajectory_parameters);
  p.computations = config.computation_parameters;
  for (std::size_t j = p.computations.size(); j < plan.computations(); ++j) {
    double hi = 0.0;
    for (const Stage& st : plan.stages) hi = std::max(hi, st.computations[j].hi);
    p.computations.push_back(hi);
  }
  if (trajectory_free && !first.trajectory.empty()) {
    const Interval& b = first.trajectory[0];
    p.lambda = b.hi > b.lo ? std::clamp((p.trajectory[0] - b.lo) / (b.hi - b.lo), 0.0, 1.0) : 1.0;
    p.trajectory = trajectory_at(plan, p.lambda);
  }
  return p;
}

// The stage durations at five lambdas (a free trajectory) or the one flown, the planned path and
// time at the initial parameters.
PathTable planned_table(const Plan& plan, const SimConfig& config, bool trajectory_free,
                        const InitialParameters& initial, SimulationResult& result) {
  PathTable table;
  double planned_time = 0.0;
  if (trajectory_free) {
    for (int i = 0; i <= 4; ++i) {
      table.lambdas.push_back(i / 4.0);
      double total = 0.0;
      const bool here = std::abs(i / 4.0 - initial.lambda) < 1e-12;
      table.durations.push_back(stage_durations(plan, config, trajectory_at(plan, i / 4.0), &total,
                                                here ? &result.planned_path : nullptr));
    }
    if (result.planned_path.empty()) {
      double total = 0.0;
      stage_durations(plan, config, initial.trajectory, &total, &result.planned_path);
    }
    for (double d : table.at(initial.lambda)) planned_time += d;
  } else {
    table.lambdas.push_back(initial.lambda);
    table.durations.push_back(
        stage_durations(plan, config, initial.trajectory, &planned_time, &result.planned_path));
  }
  for (const StageField& f : stage_fields(plan, initial.trajectory))
    result.planned_triggers.push_back(f.trigger);
  result.planned_time_s = planned_time;
  return table;
}

// The relative error of the energy predicted along the flight against what it took, after the
// first period (the samples kept); undefined for a flight that did not finish.
void prediction_errors(SimulationResult& result) {
  double sum = 0.0;
  std::size_t count = 0;
  for (const FlightSample& sample : result.samples) {
    if (sample.t_s < result.first_period_s || result.energy_j <= 0.0) continue;
    const double err = std::abs(sample.predicted_total_j - result.energy_j) / result.energy_j;
    sum += err;
    ++count;
    result.max_relative_error = std::max(result.max_relative_error, err);
  }
  result.mean_relative_error = count > 0 ? sum / static_cast<double>(count) : 0.0;
  if (result.status != SimulationEnd::completed)  // the prediction was for the whole mission
    result.mean_relative_error = result.max_relative_error = std::nan("");
}

}  // namespace

SimulationResult simulate(const Plan& plan, const SimConfig& config,
                          const std::function<void(double)>& progress, const SampleSink& sink) {
  check_config(plan, config);
  const double dt = config.time_step_s;
  const Freedom free = freedom_of(plan, config);
  const bool replanning = config.replan && (free.trajectory || free.computations);
  const InitialParameters initial = initial_parameters(plan, config, free.trajectory);

  SimulationResult result;
  const PathTable table = planned_table(plan, config, free.trajectory, initial, result);
  const double planned_time = result.planned_time_s;
  result.first_period_s = config.initial_period_s;

  // The parts, on the flight's clock.
  Flight flight(stage_fields(plan, initial.trajectory), config);
  flight.trigger();
  Parameters params(plan, config, free.trajectory, initial.trajectory, initial.computations,
                    initial.lambda, flight.stage());
  PowerMeter meter(config);
  EnergyModel model(config);
  const Outlook outlook(plan, config, table);
  Replanner replanner(plan, config, free.trajectory);
  Charge charge{config.battery.initial_soc, 0.0};
  Recorder recorder(result, sink, static_cast<int>(plan.stages.size()) - 1);
  result.control.push_back({0.0, params.trajectory(), params.computations(), true});

  auto predicted_total_j = [&] {
    if (flight.done()) return charge.energy_j;
    return charge.energy_j + outlook.rest_energy_j(outlook.rest_from(flight), params.lambda(),
                                                   params.trajectory(), params.computations(),
                                                   params.power_now(), flight.time_s(), model);
  };

  result.status = SimulationEnd::completed;
  StepKinematics k{};
  double measured = 0.0, next_output = 0.0, next_progress = 0.0;
  while (!flight.done()) {
    if (flight.time_s() >= config.max_time_s) {
      result.status = SimulationEnd::time_limit;
      break;
    }
    const double t = flight.time_s();
    const int stage = flight.stage();
    params.begin_step(stage, t, flight, result.control);
    if (replanning && model.started())
      replanner.maybe_replan(t, stage, charge.soc, flight, params, outlook, model, result);
    k = flight.step(dt);
    measured = meter.measure(t, k, params.power_now());
    const double power = model.update(t, measured, params.step_w(), params.power_now());
    charge.drain(config.battery, power, dt, t, result.reserve_crossed_s);
    params.accumulate(dt);
    flight.trigger();
    ++result.steps;
    const double now = flight.time_s();
    if (now + 1e-9 >= next_output || flight.done() || charge.soc <= 0.0) {
      recorder.record(flight, k, measured, charge, model, predicted_total_j());
      next_output += config.output_interval_s;
    }
    if (progress && now >= next_progress) {
      progress(std::min(1.0, now / std::max(planned_time, dt)));
      next_progress = now + 0.01 * planned_time;
    }
    if (charge.soc <= 0.0) {
      result.status = SimulationEnd::battery_empty;
      break;
    }
  }
  if (model.started() && recorder.last_recorded_t_s() < flight.time_s())
    recorder.record(flight, k, measured, charge, model, predicted_total_j());
  recorder.finish();

  result.stages = flight.entries();
  result.flight_time_s = flight.time_s();
  result.energy_j = charge.energy_j;
  result.final_soc = charge.soc;
  result.mean_power_w = result.flight_time_s > 0 ? charge.energy_j / result.flight_time_s : 0.0;
  result.corrections = model.started() ? model.estimator().corrections() : 0;
  result.final_period_s =
      model.started() ? model.estimator().model().period_s : config.initial_period_s;
  result.mean_trajectory = params.mean_trajectory(std::max(result.flight_time_s, dt));
  result.mean_computations = params.mean_computations(std::max(result.flight_time_s, dt));
  prediction_errors(result);
  if (progress) progress(1.0);
  return result;
}

const char* to_string(SimulationEnd status) {
  switch (status) {
    case SimulationEnd::completed:
      return "completed";
    case SimulationEnd::battery_empty:
      return "battery_empty";
    case SimulationEnd::time_limit:
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
