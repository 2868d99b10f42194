#include "swath/control/scheduler.hpp"

namespace swath::control {

std::optional<TimeTriggeredScheduler> TimeTriggeredScheduler::at_rate(double rate_hz,
                                                                      SimTime phase_ns) {
  const SimTime period = vehicle::period_of_rate(rate_hz);
  if (period <= 0 || phase_ns < 0) return std::nullopt;
  return TimeTriggeredScheduler(period, phase_ns);
}

}  // namespace swath::control
