#pragma once
// When the control task runs (docs/swath-control.md). A scheduler is told what happens — sensor
// samples, setpoint changes, executions starting and ending — and says when it next wants an
// execution and why. The time-triggered scheduler ignores the events; the reactive one (part 2) is
// driven by them, behind the same interface.

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>

#include "swath/vehicle/clock.hpp"

namespace swath::control {

using vehicle::SimTime;

/// No release pending.
inline constexpr SimTime kNever = std::numeric_limits<SimTime>::max();

/// Why an execution was requested ("executions by cause", docs/swath-control.md, opening section).
enum class ReleaseCause : std::uint8_t { time_triggered, boot, trigger, failsafe, setpoint };

/// One sensor sample as a reactive scheduler sees it: the (filtered) value over the sensor's axes.
struct SensorSample {
  SimTime time_ns = 0;
  std::size_t sensor = 0;         ///< index in the vehicle's sensor list
  std::array<double, 6> value{};  ///< the first `axes` entries are used
  std::size_t axes = 0;           ///< [1, 6]
};

class Scheduler {
 public:
  virtual ~Scheduler() = default;

  /// The instant of the next requested release, ≥ the last event seen; kNever if none.
  virtual SimTime next_release_ns() const = 0;
  /// The caller's clock has reached next_release_ns(): the release is taken (handed to the flight
  /// computer) and the scheduler moves on. Returns its cause.
  virtual ReleaseCause take_release() = 0;

  /// Events (a time-triggered scheduler ignores them).
  virtual void on_sample(const SensorSample& /*sample*/) {}
  virtual void on_setpoint_change(SimTime /*t_ns*/) {}
  virtual void on_execution_start(SimTime /*t_ns*/) {}
  /// `output_changed`: some pulse moved by ≥ change_threshold_us.
  virtual void on_execution_end(SimTime /*t_ns*/, bool /*output_changed*/) {}

  /// Refits of trigger models, run by the caller as background work on the flight computer: when
  /// the next is due (kNever: none); begin_refit() at that instant returns its data points (the
  /// work's size) and end_refit() applies the new models when the computer has done it.
  virtual SimTime next_refit_ns() const { return kNever; }
  virtual std::int64_t begin_refit(SimTime /*t_ns*/) { return 0; }
  virtual void end_refit(SimTime /*t_ns*/) {}
  /// Whether samples of vehicle sensor `sensor` are checked for triggers (they then cost the
  /// computer trigger_check_cycles each).
  virtual bool is_trigger_sensor(std::size_t /*sensor*/) const { return false; }
};

/// Time-triggered ("TT", docs/swath-control.md, 'Reactive control and paper 002's experiment'): a
/// release at phase_ns + k · period_ns for k = 0, 1, ….
class TimeTriggeredScheduler final : public Scheduler {
 public:
  /// `period_ns` > 0; `phase_ns` ≥ 0.
  TimeTriggeredScheduler(SimTime period_ns, SimTime phase_ns = 0)
      : period_ns_(period_ns), next_ns_(phase_ns) {}
  /// The scheduler for `rate_hz`, or nullopt when 1/rate_hz is not a whole number of ns, which is
  /// refused.
  static std::optional<TimeTriggeredScheduler> at_rate(double rate_hz, SimTime phase_ns = 0);

  SimTime next_release_ns() const override { return next_ns_; }
  ReleaseCause take_release() override {
    next_ns_ += period_ns_;
    return ReleaseCause::time_triggered;
  }
  SimTime period_ns() const { return period_ns_; }

 private:
  SimTime period_ns_;
  SimTime next_ns_;
};

/// The control task as a data-dependency graph (paper 002 §6, "RP-Embedded"; docs/swath-control.md,
/// 'Partial and whole execution of the control graph'): its inputs, its nodes in a topological
/// order and each node's share of an execution's cycles (computer.control_cycles). It is a cost
/// model: the simulated task computes every step at every execution; what differs between partial
/// and whole execution is the CPU time the flight computer is charged for.
enum class GraphInput : std::uint8_t { gyro, accel, mag, baro, position, setpoint };
inline constexpr std::size_t kGraphInputs = 6;

struct GraphNode {
  const char* name;
  double share;            ///< of control_cycles; the shares sum to 1
  unsigned inputs;         ///< bit k: GraphInput k is read by the node
  std::uint32_t upstream;  ///< bit j: node j's output is read by the node (j before it)
};

/// The seven steps of ControlTask::execute as nodes, in order (control_task.hpp).
std::span<const GraphNode> control_graph();

/// The nodes an execution re-runs when the inputs in `changed_inputs` (bit k: GraphInput k)
/// changed: every node reading one of them and every node downstream of those (RP's propagation).
std::uint32_t nodes_to_run(unsigned changed_inputs);

/// The cycles of the nodes in `nodes` (bit j: node j) when the whole graph costs `control_cycles`:
/// node j costs round(share_j · control_cycles), the last node the rest, so that the whole graph
/// costs control_cycles exactly.
std::int64_t graph_cycles(std::uint32_t nodes, std::int64_t control_cycles);

/// All nodes.
std::uint32_t whole_graph();

}  // namespace swath::control
