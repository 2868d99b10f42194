#pragma once
// The flight computer (docs/swath-control.md): one core at clock_hz running the
// sensor drivers, the control task, the trigger models' refits and periodic background work, by
// fixed priority (drivers > control > refit > background) with preemption, costs in cycles. It
// counts missed time-triggered releases as overruns and integrates its power
// P_cpu = idle_w + (active_w − idle_w) · busy.
//
// A higher priority preempts a lower one at once, except that control waits for a background job
// already begun when control_preempts_background is false. Background tasks rank among themselves
// in file order; a release that finds its previous instance unfinished is skipped (counted).
//
// Event-driven: the simulation calls sample(), request_control() and request_refit() at its
// current instant and advance() to move the core on; advance() stops at every control start (take
// the input snapshot then) and end (the outputs are ready then).

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "swath/control/scheduler.hpp"

namespace swath::control {

/// Periodic background work (`computer.background[]`, docs/swath-control.md, 'Vehicle, scheduler
/// and environment files').
struct BackgroundTask {
  std::string name;
  double rate_hz = 10;      ///< releases per second, (0, 1e6]; the first at t = 0
  std::int64_t cycles = 0;  ///< per release, ≥ 0
};

/// `computer.*` (docs/swath-control.md, 'Vehicle, scheduler and environment files').
struct ComputerSettings {
  double clock_hz = 168e6;                    ///< core clock, Hz, > 0
  std::int64_t control_cycles = 120'000;      ///< one control execution, cycles, ≥ 0
  std::int64_t dispatch_cycles = 2'000;       ///< reactive dispatch per execution, cycles, ≥ 0
  std::int64_t driver_cycles = 1'500;         ///< per sensor sample, cycles, ≥ 0
  std::int64_t trigger_check_cycles = 100;    ///< per sample of a trigger sensor, cycles, ≥ 0
  std::int64_t refit_cycles_per_point = 300;  ///< per data point of a refit, cycles, ≥ 0
  double idle_w = 0.15;                       ///< board power asleep, W, ≥ 0
  double active_w = 0.40;                     ///< board power at full speed, W, ≥ idle_w
  bool control_preempts_background = true;    ///< false: a started background job runs to its end
  std::vector<BackgroundTask> background = {
      {"logging", 50, 20'000}, {"telemetry", 10, 60'000}, {"gps_parse", 10, 30'000}};
};

/// What advance() stopped at.
struct ComputerEvent {
  enum class Type : std::uint8_t { control_start, control_end, refit_end };
  Type type = Type::control_start;
  SimTime time_ns = 0;     ///< the instant of the event
  SimTime request_ns = 0;  ///< when the execution (or refit) was requested
  ReleaseCause cause = ReleaseCause::time_triggered;  ///< control: the first cause of the request
  int merged = 0;  ///< control: later requests that joined this one
};

/// Running totals.
struct ComputerStats {
  SimTime busy_ns = 0;                   ///< time the core did work
  std::int64_t executions = 0;           ///< control executions completed
  std::int64_t overruns = 0;             ///< time-triggered releases that found a request waiting
  std::int64_t merged = 0;               ///< other requests merged into a waiting one
  std::int64_t driver_jobs = 0;          ///< samples processed
  std::int64_t refits = 0;               ///< refits completed
  std::int64_t background_released = 0;  ///< every release, run or skipped
  std::int64_t background_completed = 0;
  std::int64_t background_skipped = 0;  ///< releases that found their previous instance unfinished
  /// Release to completion of the completed background jobs: sum and largest, ns.
  SimTime background_latency_sum_ns = 0, background_latency_max_ns = 0;
};

class FlightComputer {
 public:
  /// `settings` valid as documented.
  explicit FlightComputer(const ComputerSettings& settings);

  /// The core's time: everything before it has been simulated.
  SimTime now_ns() const { return now_ns_; }

  /// Runs the core up to `t_ns` (≥ now_ns(), else nothing happens). Returns the first control
  /// start, control end or refit end on the way, with the core stopped there; nullopt once the
  /// core has reached t_ns. Call it again until it returns nullopt.
  std::optional<ComputerEvent> advance(SimTime t_ns);

  /// At now_ns(): a sensor sample to process (driver_cycles, plus trigger_check_cycles if
  /// `trigger_check`).
  void sample(bool trigger_check = false);
  /// At now_ns(): a request to run the control task (control_cycles, plus dispatch_cycles if
  /// `dispatch`). One request may wait while an execution runs; a request that finds one waiting
  /// (or one released but not yet started) joins it, and counts as an overrun when it is a
  /// time-triggered release.
  void request_control(ReleaseCause cause, bool dispatch = false);
  /// At a control start (advance() returned it, nothing of it has run): the execution costs
  /// `cycles` instead of what was requested (partial execution of the control graph).
  void set_running_control_cycles(std::int64_t cycles);
  /// At now_ns(): a refit over `points` data points (refit_cycles_per_point each).
  void request_refit(std::int64_t points);

  /// Whether an execution has been requested and not yet finished.
  bool control_pending() const { return control_.has_value(); }

  const ComputerStats& stats() const { return stats_; }
  /// The board's energy since t = 0, J: idle_w · now + (active_w − idle_w) · busy.
  double energy_j() const;
  /// The duration of `cycles` on this core, ns, rounded up.
  SimTime duration_ns(std::int64_t cycles) const;

 private:
  struct Job {
    SimTime request_ns = 0;
    SimTime remaining_ns = 0;
    bool started = false;
    ReleaseCause cause = ReleaseCause::time_triggered;
    int merged = 0;
  };
  struct Periodic {
    SimTime period_ns = 0, next_release_ns = 0;
    std::optional<Job> job;
  };
  enum class Pick { none, driver, control, refit, background };

  Pick pick(std::size_t& background_index);
  void release_background();
  SimTime next_background_release() const;

  ComputerSettings settings_;
  SimTime now_ns_ = 0;
  std::deque<Job> drivers_, refits_;
  std::optional<Job> control_, control_waiting_;
  std::vector<Periodic> background_;
  ComputerStats stats_;
};

}  // namespace swath::control
