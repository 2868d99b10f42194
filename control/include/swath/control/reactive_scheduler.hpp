#pragma once
// Reactive control execution (paper 002 §4–5, docs/swath-control.md): the control task runs when a
// sensor's change x_s makes a new decision likely (L_s(x) > P_run, tested as x > x*_s), batched at
// the hyperperiod of the fast sensors (capped by max_wait_s), with a time-triggered boot that
// gathers the first data, a failsafe watchdog, executions forced by a new setpoint leg, the
// feedback of executions' outcomes into per-sensor data sets, and periodic refits that run as
// background work on the flight computer.
//
// Three guards keep the feedback loop from ratcheting itself into a crash (paper 002's rule, which
// feeds back only false positives above x*, raises x* at every refit until β2 < 0): the default
// feedback `all` labels every trigger execution for each sensor that triggered it and every
// failsafe execution for each sensor with a new sample (unbiased: selection on x does not bias a
// logistic fit of the label given x); a model with β2 ≤ 0 never fires at x = 0 (it would fire
// on every sample, changed or not); and executions triggered by slow sensors alone (below
// accumulation.min_rate_hz, e.g. a 10 Hz GPS) do not reset the watchdog, so the failsafe still runs
// the loop at its rate.

#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "swath/control/config.hpp"
#include "swath/control/logistic.hpp"
#include "swath/control/scheduler.hpp"

namespace swath::control {

/// A trigger sensor as the scheduler knows it.
struct TriggerSensor {
  std::string name;
  std::size_t index = 0;  ///< in the vehicle's sensor list (SensorSample::sensor)
  SimTime period_ns = 0;
  GraphInput input = GraphInput::gyro;  ///< the control graph's input it feeds
};

/// Per-sensor running figures (summary.json's `triggers`).
struct TriggerStats {
  std::int64_t samples = 0, triggers = 0, refits = 0;
  LogisticModel model;
  double threshold = 0;  ///< x* in force (+∞: never)
  std::size_t dataset = 0;
};

/// Feedback totals (summary.json's `feedback`).
struct FeedbackStats {
  std::int64_t false_positives = 0;  ///< attributed trigger executions, output unchanged
  std::int64_t false_negatives = 0;  ///< failsafe executions that changed it
  std::int64_t true_positives = 0;
  /// Executions caused by triggers alone whose triggers are attributed: to each triggering sensor
  /// (`all`), or to one sensor only (`errors`, the paper's rule: several sensors are excluded).
  std::int64_t single_trigger_executions = 0;
  std::int64_t multi_cause_excluded = 0;  ///< several causes: no feedback, as in paper 002
  /// Single-trigger executions and their false positives in the first 10 s after the boot, and
  /// from 60 s after it (paper 002 §7.3: 7 % → 2 %).
  std::int64_t after_boot = 0, after_boot_fp = 0, steady = 0, steady_fp = 0;
};

/// What the scheduler knew of the execution that just ended (executions.csv).
struct ExecutionRecord {
  unsigned causes = 0;      ///< bits 1 tt, 2 boot, 4 trigger, 8 failsafe, 16 setpoint
  int trigger_sensor = -1;  ///< the one sensor whose trigger caused it; −1 none, −2 several
  std::uint64_t trigger_sensors = 0;  ///< bit k: trigger sensor k's trigger caused it
  bool false_positive = false, false_negative = false;
  std::vector<double> x;  ///< each trigger sensor's change at the start
};

class ReactiveScheduler final : public Scheduler {
 public:
  /// `settings` valid as docs/swath-control.md, 'Vehicle, scheduler and environment files' says;
  /// `sensors` the vehicle's trigger sensors (at least one); `rate_hz` the file's TT rate (the
  /// boot's when boot_rate_hz is 0).
  ReactiveScheduler(const ReactiveSettings& settings, std::vector<TriggerSensor> sensors,
                    double rate_hz);

  SimTime next_release_ns() const override;
  ReleaseCause take_release() override;
  void on_sample(const SensorSample& sample) override;
  void on_setpoint_change(SimTime t_ns) override;
  void on_execution_start(SimTime t_ns) override;
  void on_execution_end(SimTime t_ns, bool output_changed) override;
  SimTime next_refit_ns() const override { return next_refit_ns_; }
  std::int64_t begin_refit(SimTime t_ns) override;
  void end_refit(SimTime t_ns) override;
  bool is_trigger_sensor(std::size_t sensor) const override;

  const ExecutionRecord& last_execution() const { return record_; }
  /// The execution under way (after on_execution_start): the control graph's inputs that caused
  /// it (bit k: GraphInput k), or nullopt when a cause runs the whole graph (boot, failsafe).
  std::optional<unsigned> running_graph_inputs() const;
  /// Triggers per sensor since the last call (rate.csv), and reset.
  std::vector<int> take_trigger_counts();
  const std::vector<TriggerStats>& stats() const { return stats_; }
  const FeedbackStats& feedback() const { return feedback_; }
  const std::vector<TriggerSensor>& sensors() const { return sensors_; }
  /// The hyperperiod of the fast trigger sensors, ns.
  SimTime hyperperiod_ns() const { return hyperperiod_ns_; }

 private:
  struct PerSensor {
    std::array<double, 6> latest{}, reference{}, previous{};
    std::size_t axes = 0;
    bool has_latest = false, has_reference = false, new_sample = false;
    double change_at_start = 0;  // x_s of the execution under way
    bool new_at_start = false;   // a sample arrived before that execution
    LogisticModel model;
    double threshold = 0;
    double threshold_square = 0;        // largest_square_within(threshold), for fires' fast path
    std::vector<TriggerPoint> boot;     // the boot's points
    std::deque<TriggerPoint> ring;      // feedback, bounded
    std::vector<TriggerPoint> fitting;  // the data of the refit under way (mle)
    // The logit fits depend only on the multiset of points, not their order (logistic.cpp's
    // groups): boot ∪ ring kept sorted by (x, changed) as of the last refit, with the points added
    // and dropped since, merged in at the next refit (O(n) instead of sorting every refit).
    std::vector<TriggerPoint> sorted, added, dropped;
    bool unsortable = false;  // a NaN x was seen: fit the unsorted copy as it comes
    int counted = 0;
    bool fast = false;  // at or above accumulation.min_rate_hz: its executions reset the watchdog
  };
  enum CauseBit : unsigned {
    kTimeTriggered = 1,
    kBoot = 2,
    kTrigger = 4,
    kFailsafe = 8,
    kSetpoint = 16
  };

  bool booting(SimTime t) const { return t < boot_end_ns_; }
  double change(const PerSensor& s) const;
  double change_square(const PerSensor& s) const;
  void set_threshold(PerSensor& s, double threshold);
  bool fires(const PerSensor& s, double x) const;
  void request(SimTime at, unsigned cause);
  void add_point(PerSensor& s, TriggerPoint p);
  void add_boot_point(PerSensor& s, TriggerPoint p);
  bool fits_sorted(const PerSensor& s) const;
  void update_sorted(PerSensor& s);
  void feed_back(bool output_changed);
  bool resets_watchdog() const;

  ReactiveSettings settings_;
  std::vector<TriggerSensor> sensors_;
  std::vector<PerSensor> state_;
  std::vector<TriggerStats> stats_;
  std::vector<int> index_of_sensor_;  // vehicle sensor index → ours (−1: not a trigger)
  FeedbackStats feedback_;
  ExecutionRecord record_;
  SimTime hyperperiod_ns_ = 0, max_wait_ns_ = 0, boot_period_ns_ = 0, boot_end_ns_ = 0;
  SimTime failsafe_ns_ = 0, refit_period_ns_ = 0;
  SimTime next_boot_ns_ = 0, request_ns_ = kNever, last_start_ns_ = 0, next_refit_ns_ = kNever;
  SimTime failsafe_due_ns_ = 0;
  bool failsafe_armed_ = false;
  unsigned pending_ = 0;  // causes of the request not yet taken
  unsigned taken_ = 0;    // causes taken since the last execution start
  unsigned running_ = 0;  // causes of the execution under way
  // The sensors whose triggers caused the pending request / the releases taken / the execution
  // under way, bit k for trigger sensor k.
  std::uint64_t pending_triggers_ = 0, taken_triggers_ = 0, running_triggers_ = 0;
  double p_logit_ = 0;
  std::vector<TriggerPoint> merged_;  // update_sorted's scratch
};

}  // namespace swath::control
