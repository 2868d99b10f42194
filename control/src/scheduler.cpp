#include "swath/control/scheduler.hpp"

#include <cmath>

namespace swath::control {

std::optional<TimeTriggeredScheduler> TimeTriggeredScheduler::at_rate(double rate_hz,
                                                                      SimTime phase_ns) {
  const SimTime period = vehicle::period_of_rate(rate_hz);
  if (period <= 0 || phase_ns < 0) return std::nullopt;
  return TimeTriggeredScheduler(period, phase_ns);
}

namespace {

constexpr unsigned bit(GraphInput i) {
  return 1u << static_cast<unsigned>(i);
}

// The data dependencies of ControlTask::execute (control_task.cpp). The attitude filter's output
// reaches every later step: the position filter rotates the accelerometer's Δv with it, the
// velocity step projects the thrust on its body z, the attitude and rate steps compare with it.
// The shares are assumed (the paper gives none): the two filters and the mixer are the
// heavier steps (matrix and quaternion work), the PIDs the lighter.
constexpr std::array<GraphNode, 7> kGraph{{
    {"attitude_filter", 0.20, bit(GraphInput::gyro) | bit(GraphInput::accel) | bit(GraphInput::mag),
     0},
    {"position_filter", 0.20,
     bit(GraphInput::accel) | bit(GraphInput::baro) | bit(GraphInput::position), 1u << 0},
    {"position_control", 0.05, bit(GraphInput::setpoint), 1u << 1},
    {"velocity_control", 0.15, bit(GraphInput::setpoint), (1u << 0) | (1u << 1) | (1u << 2)},
    {"attitude_control", 0.10, bit(GraphInput::setpoint), (1u << 0) | (1u << 3)},
    {"rate_control", 0.10, bit(GraphInput::gyro), (1u << 0) | (1u << 4)},
    {"mixer", 0.20, 0, (1u << 3) | (1u << 5)},
}};

}  // namespace

std::span<const GraphNode> control_graph() {
  return kGraph;
}

std::uint32_t whole_graph() {
  return (1u << kGraph.size()) - 1;
}

std::uint32_t nodes_to_run(unsigned changed_inputs) {
  std::uint32_t run = 0;
  // One pass in topological order: a node's upstream nodes are decided before it.
  for (std::size_t j = 0; j < kGraph.size(); ++j)
    if ((kGraph[j].inputs & changed_inputs) != 0 || (kGraph[j].upstream & run) != 0) run |= 1u << j;
  return run;
}

std::int64_t graph_cycles(std::uint32_t nodes, std::int64_t control_cycles) {
  std::int64_t total = 0, assigned = 0;
  for (std::size_t j = 0; j < kGraph.size(); ++j) {
    const std::int64_t cycles =
        j + 1 == kGraph.size()
            ? control_cycles - assigned
            : std::llround(kGraph[j].share * static_cast<double>(control_cycles));
    assigned += cycles;
    if (nodes >> j & 1) total += cycles;
  }
  return total;
}

}  // namespace swath::control
