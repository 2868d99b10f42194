#include "swath/control/reactive_scheduler.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>

namespace swath::control {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr SimTime kFeedbackWindowAfterBoot_ns = 10 * vehicle::kNanosecondsPerSecond;
constexpr SimTime kSteadyAfterBoot_ns = 60 * vehicle::kNanosecondsPerSecond;

int bits(std::uint64_t v) {
  return __builtin_popcountll(v);
}

// The one sensor of a mask, −1 for none, −2 for several.
int single_sensor(std::uint64_t mask) {
  if (mask == 0) return -1;
  if (bits(mask) > 1) return -2;
  return __builtin_ctzll(mask);
}

}  // namespace

ReactiveScheduler::ReactiveScheduler(const ReactiveSettings& settings,
                                     std::vector<TriggerSensor> sensors, double rate_hz)
    : settings_(settings), sensors_(std::move(sensors)) {
  state_.resize(sensors_.size());
  stats_.resize(sensors_.size());
  for (std::size_t k = 0; k < sensors_.size(); ++k) {
    const std::size_t index = sensors_[k].index;
    if (index_of_sensor_.size() <= index) index_of_sensor_.resize(index + 1, -1);
    index_of_sensor_[index] = static_cast<int>(k);
    state_[k].fast = 1e9 / static_cast<double>(sensors_[k].period_ns) + 1e-9 >=
                     settings_.accumulation_min_rate_hz;
  }
  p_logit_ = std::log(settings_.p_run / (1 - settings_.p_run));
  // The hyperperiod of the fast trigger sensors (docs/swath-control.md, 'Reactive control and paper
  // 002's experiment': the literal one, with a 10 Hz GPS, would hold every trigger for up to
  // 100 ms).
  hyperperiod_ns_ = 1;
  for (const TriggerSensor& s : sensors_) {
    const double rate = 1e9 / static_cast<double>(s.period_ns);
    if (rate + 1e-9 >= settings_.accumulation_min_rate_hz)
      hyperperiod_ns_ = std::lcm(hyperperiod_ns_, s.period_ns);
  }
  max_wait_ns_ = vehicle::from_seconds(settings_.accumulation_max_wait_s);
  boot_period_ns_ =
      vehicle::period_of_rate(settings_.boot_rate_hz > 0 ? settings_.boot_rate_hz : rate_hz);
  if (boot_period_ns_ <= 0) boot_period_ns_ = vehicle::period_of_rate(400);
  boot_end_ns_ = vehicle::from_seconds(settings_.boot_s);
  failsafe_ns_ = std::max<SimTime>(vehicle::from_seconds(settings_.failsafe_s), 1);
  refit_period_ns_ = std::max<SimTime>(vehicle::from_seconds(settings_.fit_refit_period_s), 1);
  for (std::size_t k = 0; k < sensors_.size(); ++k) {
    PerSensor& s = state_[k];
    set_threshold(s, kInfinity);  // no trigger before a model exists
    s.model.beta1 = -1e300;       // L = 0
    for (const InitialModel& m : settings_.initial_models)
      if (m.sensor == sensors_[k].name) {
        s.model = {m.beta1, m.beta2, false, 0};
        set_threshold(s, trigger_threshold(s.model, settings_.p_run));
      }
    stats_[k].model = s.model;
    stats_[k].threshold = s.threshold;
  }
  // The watchdog runs from the boot's end (the boot's own releases come first).
  failsafe_armed_ = true;
  failsafe_due_ns_ = boot_end_ns_;
  next_refit_ns_ = boot_end_ns_ > 0 ? boot_end_ns_ : refit_period_ns_;
  if (settings_.fit_feedback == FeedbackRule::none && boot_end_ns_ == 0) next_refit_ns_ = kNever;
}

bool ReactiveScheduler::is_trigger_sensor(std::size_t sensor) const {
  return sensor < index_of_sensor_.size() && index_of_sensor_[sensor] >= 0;
}

SimTime ReactiveScheduler::next_release_ns() const {
  SimTime t = request_ns_;
  if (next_boot_ns_ < boot_end_ns_) t = std::min(t, next_boot_ns_);
  // The failsafe: a watchdog since the last execution started, or a fixed period.
  if (failsafe_armed_) t = std::min(t, std::max(failsafe_due_ns_, boot_end_ns_));
  return t;
}

ReleaseCause ReactiveScheduler::take_release() {
  const SimTime t = next_release_ns();
  unsigned cause = 0;
  if (next_boot_ns_ < boot_end_ns_ && next_boot_ns_ == t) {
    cause |= kBoot;
    next_boot_ns_ += boot_period_ns_;
  }
  if (request_ns_ == t) {
    cause |= pending_;
    pending_ = 0;
    request_ns_ = kNever;
    taken_triggers_ |= pending_triggers_;
    pending_triggers_ = 0;
  }
  if (failsafe_armed_ && std::max(failsafe_due_ns_, boot_end_ns_) == t) {
    cause |= kFailsafe;
    if (settings_.failsafe_mode == FailsafeMode::periodic) {
      failsafe_due_ns_ += failsafe_ns_;
    } else {
      failsafe_armed_ = false;  // re-armed when an execution starts
    }
  }
  taken_ |= cause;
  if (cause & kBoot) return ReleaseCause::boot;
  if (cause & kTrigger) return ReleaseCause::trigger;
  if (cause & kFailsafe) return ReleaseCause::failsafe;
  if (cause & kSetpoint) return ReleaseCause::setpoint;
  return ReleaseCause::time_triggered;
}

double ReactiveScheduler::change_square(const PerSensor& s) const {
  const auto& ref =
      settings_.delta_reference == DeltaReference::last_sample ? s.previous : s.reference;
  double sum = 0;
  for (std::size_t a = 0; a < s.axes; ++a) sum += (s.latest[a] - ref[a]) * (s.latest[a] - ref[a]);
  return sum;
}

double ReactiveScheduler::change(const PerSensor& s) const {
  return std::sqrt(change_square(s));
}

void ReactiveScheduler::set_threshold(PerSensor& s, double threshold) {
  s.threshold = threshold;
  s.threshold_square = largest_square_within(threshold);
}

bool ReactiveScheduler::fires(const PerSensor& s, double x) const {
  if (s.model.beta2 > 0) return x > s.threshold;
  // A model in which a larger change makes a new output no more likely: L(x) > P_run evaluated
  // directly, but never for a sample that did not change (x = 0), so that a sensor whose model
  // has drifted to L(0) > P_run cannot fire on every unchanged sample.
  return x > 0 && s.model.beta1 + s.model.beta2 * x > p_logit_;
}

void ReactiveScheduler::request(SimTime at, unsigned cause) {
  request_ns_ = std::min(request_ns_, at);
  pending_ |= cause;
}

void ReactiveScheduler::on_sample(const SensorSample& sample) {
  if (!is_trigger_sensor(sample.sensor)) return;
  const auto k = static_cast<std::size_t>(index_of_sensor_[sample.sensor]);
  PerSensor& s = state_[k];
  ++stats_[k].samples;
  if (settings_.delta_reference == DeltaReference::last_sample)
    s.previous = s.has_latest ? s.latest : sample.value;
  s.axes = std::min<std::size_t>(sample.axes, 6);
  // The `axes` entries used, one at a time: the caller has just written them one at a time, and
  // a wider load across those stores would wait for them to reach the cache (~10 cycles).
  for (std::size_t a = 0; a < s.axes; ++a) s.latest[a] = sample.value[a];
  s.has_latest = s.new_sample = true;
  const SimTime t = sample.time_ns;
  if (booting(t) || !s.has_reference) return;
  // With a positive slope a sample fires when x > x*, that is when its sum of squares exceeds
  // x*'s bound (the same decision without a square root: most samples do not fire).
  if (s.model.beta2 > 0 && !(change_square(s) > s.threshold_square)) return;
  if (!(s.model.beta2 > 0) && !fires(s, change(s))) return;
  ++stats_[k].triggers;
  ++s.counted;
  // Batched at the hyperperiod, never held longer than max_wait_s.
  const SimTime batch = (t + hyperperiod_ns_ - 1) / hyperperiod_ns_ * hyperperiod_ns_;
  request(std::min(batch, t + max_wait_ns_), kTrigger);
  pending_triggers_ |= std::uint64_t{1} << k;
}

void ReactiveScheduler::on_setpoint_change(SimTime t_ns) {
  if (settings_.setpoint_forces_execution && !booting(t_ns)) request(t_ns, kSetpoint);
}

void ReactiveScheduler::on_execution_start(SimTime t_ns) {
  running_ = taken_;
  running_triggers_ = taken_triggers_;
  taken_ = 0;
  taken_triggers_ = 0;
  last_start_ns_ = t_ns;
  if (settings_.failsafe_mode == FailsafeMode::watchdog) {
    if (resets_watchdog()) {
      failsafe_due_ns_ = t_ns + failsafe_ns_;
      failsafe_armed_ = true;
    }
  } else if (!failsafe_armed_) {
    failsafe_due_ns_ = std::max(boot_end_ns_, t_ns + failsafe_ns_);
    failsafe_armed_ = true;
  }
  for (PerSensor& s : state_) {
    s.change_at_start = s.has_reference ? change(s) : 0.0;
    s.new_at_start = s.new_sample;
    if (s.has_latest) {
      s.reference = s.latest;
      s.has_reference = true;
    }
    s.new_sample = false;
  }
}

void ReactiveScheduler::add_point(PerSensor& s, TriggerPoint p) {
  const bool sorted = fits_sorted(s);
  s.ring.push_back(p);
  if (sorted) s.added.push_back(p);
  while (s.ring.size() > static_cast<std::size_t>(settings_.fit_dataset_capacity)) {
    if (sorted) s.dropped.push_back(s.ring.front());
    s.ring.pop_front();
  }
}

void ReactiveScheduler::add_boot_point(PerSensor& s, TriggerPoint p) {
  s.boot.push_back(p);
  if (fits_sorted(s)) s.added.push_back(p);
}

bool ReactiveScheduler::fits_sorted(const PerSensor& s) const {
  return settings_.fit_method != FitMethod::mle && !s.unsortable;
}

// s.sorted becomes (s.sorted ∪ s.added) − s.dropped, as multisets ordered by (x, changed).
void ReactiveScheduler::update_sorted(PerSensor& s) {
  const auto before = [](const TriggerPoint& a, const TriggerPoint& b) {
    return a.x < b.x || (a.x == b.x && a.changed < b.changed);
  };
  for (const TriggerPoint& p : s.added)
    if (std::isnan(p.x)) s.unsortable = true;  // no order: fall back to the copy (begin_refit)
  if (s.unsortable) {
    s.added = {};
    s.dropped = {};
    return;
  }
  std::sort(s.added.begin(), s.added.end(), before);
  std::sort(s.dropped.begin(), s.dropped.end(), before);
  merged_.clear();
  std::merge(s.sorted.begin(), s.sorted.end(), s.added.begin(), s.added.end(),
             std::back_inserter(merged_), before);
  s.sorted.clear();
  std::set_difference(merged_.begin(), merged_.end(), s.dropped.begin(), s.dropped.end(),
                      std::back_inserter(s.sorted), before);
  s.added.clear();
  s.dropped.clear();
}

bool ReactiveScheduler::resets_watchdog() const {
  // Every cause but a trigger is the loop running at its rate; a trigger only when a fast sensor
  // fired (a 10 Hz GPS firing on every fix would otherwise hold off the 0.1 s failsafe forever).
  if (running_ & ~unsigned{kTrigger}) return true;
  for (std::size_t k = 0; k < state_.size(); ++k)
    if ((running_triggers_ >> k & 1) && state_[k].fast) return true;
  return running_ == 0;
}

void ReactiveScheduler::on_execution_end(SimTime t_ns, bool output_changed) {
  record_.causes = running_;
  record_.trigger_sensors = running_triggers_;
  record_.trigger_sensor = single_sensor(running_triggers_);
  record_.x.resize(state_.size());
  for (std::size_t k = 0; k < state_.size(); ++k) record_.x[k] = state_[k].change_at_start;
  const bool paper_rule = settings_.fit_feedback == FeedbackRule::errors;
  // The paper attributes an execution to a trigger only when one sensor alone caused it.
  const bool attributed = running_ == kTrigger && running_triggers_ != 0 &&
                          (!paper_rule || bits(running_triggers_) == 1);
  record_.false_positive = attributed && !output_changed;
  record_.false_negative = running_ == kFailsafe && output_changed;
  if (running_ & kBoot) {
    for (PerSensor& s : state_)
      if (s.new_at_start &&
          s.boot.size() < static_cast<std::size_t>(settings_.fit_dataset_capacity))
        add_boot_point(s, {s.change_at_start, output_changed});
    return;
  }
  if (attributed) {
    ++feedback_.single_trigger_executions;
    const SimTime since_boot = t_ns - boot_end_ns_;
    if (since_boot < kFeedbackWindowAfterBoot_ns) {
      ++feedback_.after_boot;
      if (!output_changed) ++feedback_.after_boot_fp;
    } else if (since_boot >= kSteadyAfterBoot_ns) {
      ++feedback_.steady;
      if (!output_changed) ++feedback_.steady_fp;
    }
    ++(output_changed ? feedback_.true_positives : feedback_.false_positives);
  } else if (running_ == kFailsafe) {
    if (output_changed) ++feedback_.false_negatives;
  } else if (bits(running_) > 1 || bits(running_triggers_) > 1) {
    ++feedback_.multi_cause_excluded;
  }
  feed_back(output_changed);
}

void ReactiveScheduler::feed_back(bool output_changed) {
  switch (settings_.fit_feedback) {
    case FeedbackRule::none:
      return;
    case FeedbackRule::errors:  // the paper's: false positives above x*, false negatives below
      if (running_ == kTrigger && bits(running_triggers_) == 1 && !output_changed) {
        PerSensor& s = state_[static_cast<std::size_t>(single_sensor(running_triggers_))];
        add_point(s, {s.change_at_start, false});
      } else if (running_ == kFailsafe && output_changed) {
        for (PerSensor& s : state_)
          if (s.new_at_start) add_point(s, {s.change_at_start, true});
      }
      return;
    case FeedbackRule::all:  // every outcome, for every sensor it tells something about
      if (running_ == kTrigger) {
        for (std::size_t k = 0; k < state_.size(); ++k)
          if (running_triggers_ >> k & 1)
            add_point(state_[k], {state_[k].change_at_start, output_changed});
      } else if (running_ == kFailsafe) {
        for (PerSensor& s : state_)
          if (s.new_at_start) add_point(s, {s.change_at_start, output_changed});
      }
      return;
  }
}

std::int64_t ReactiveScheduler::begin_refit(SimTime /*t_ns*/) {
  std::int64_t points = 0;
  for (PerSensor& s : state_) {
    if (fits_sorted(s)) update_sorted(s);
    if (fits_sorted(s)) {
      points += static_cast<std::int64_t>(s.sorted.size());
      continue;
    }
    s.fitting.assign(s.boot.begin(), s.boot.end());
    s.fitting.insert(s.fitting.end(), s.ring.begin(), s.ring.end());
    points += static_cast<std::int64_t>(s.fitting.size());
  }
  next_refit_ns_ = kNever;  // until this one is done
  return points;
}

void ReactiveScheduler::end_refit(SimTime t_ns) {
  for (std::size_t k = 0; k < state_.size(); ++k) {
    PerSensor& s = state_[k];
    // s.sorted does not change between begin_refit and here (points added meanwhile wait in
    // s.added), so it is the refit's snapshot as s.fitting is.
    const std::vector<TriggerPoint>& data = fits_sorted(s) ? s.sorted : s.fitting;
    if (data.empty()) continue;  // keep what there is
    s.model =
        fit_logistic(data, settings_.fit_method, settings_.fit_bins, settings_.fit_min_per_bin);
    set_threshold(s, trigger_threshold(s.model, settings_.p_run));
    stats_[k].model = s.model;
    stats_[k].threshold = s.threshold;
    stats_[k].dataset = data.size();
    ++stats_[k].refits;
    s.fitting.clear();
  }
  // `none` freezes the models after the boot's fit.
  next_refit_ns_ = settings_.fit_feedback == FeedbackRule::none ? kNever : t_ns + refit_period_ns_;
}

std::optional<unsigned> ReactiveScheduler::running_graph_inputs() const {
  if (running_ == 0 || (running_ & ~unsigned{kTrigger | kSetpoint})) return std::nullopt;
  unsigned inputs = (running_ & kSetpoint) ? 1u << static_cast<unsigned>(GraphInput::setpoint) : 0u;
  for (std::size_t k = 0; k < sensors_.size(); ++k)
    if (running_triggers_ >> k & 1) inputs |= 1u << static_cast<unsigned>(sensors_[k].input);
  return inputs;
}

std::vector<int> ReactiveScheduler::take_trigger_counts() {
  std::vector<int> out;
  for (PerSensor& s : state_) {
    out.push_back(s.counted);
    s.counted = 0;
  }
  return out;
}

}  // namespace swath::control
