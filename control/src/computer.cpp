#include "swath/control/computer.hpp"

#include <algorithm>
#include <cmath>

namespace swath::control {

FlightComputer::FlightComputer(const ComputerSettings& settings) : settings_(settings) {
  for (const BackgroundTask& task : settings_.background) {
    Periodic p;
    // A rate that does not divide a second into whole ns is rounded to the nearest ns.
    // A rate of 0 (refused by the reader) would be a task that never comes back: one release.
    p.period_ns = task.rate_hz > 0 ? std::max<SimTime>(vehicle::from_seconds(1.0 / task.rate_hz), 1)
                                   : kNever / 2;
    background_.push_back(p);
  }
}

SimTime FlightComputer::duration_ns(std::int64_t cycles) const {
  const double ns = static_cast<double>(cycles) * 1e9 / settings_.clock_hz;
  // Rounded up, ignoring the last bits of rounding (120,000 cycles at 100 MHz are 1.2 ms, not
  // 1.2 ms + 1 ns).
  return static_cast<SimTime>(std::ceil(ns * (1 - 1e-12)));
}

double FlightComputer::energy_j() const {
  return settings_.idle_w * vehicle::seconds(now_ns_) +
         (settings_.active_w - settings_.idle_w) * vehicle::seconds(stats_.busy_ns);
}

void FlightComputer::sample(bool trigger_check) {
  const std::int64_t cycles =
      settings_.driver_cycles + (trigger_check ? settings_.trigger_check_cycles : 0);
  drivers_.push_back(Job{now_ns_, duration_ns(cycles)});
}

void FlightComputer::request_control(ReleaseCause cause, bool dispatch) {
  const std::int64_t cycles = settings_.control_cycles + (dispatch ? settings_.dispatch_cycles : 0);
  const Job job{now_ns_, duration_ns(cycles), false, cause, 0};
  // The request that later causes join: the waiting one, or the current one if it has not begun.
  std::optional<Job>* open = nullptr;
  if (control_ && !control_->started)
    open = &control_;
  else if (control_waiting_)
    open = &control_waiting_;
  if (open) {
    ++(*open)->merged;
    ++(cause == ReleaseCause::time_triggered ? stats_.overruns : stats_.merged);
    return;
  }
  (control_ ? control_waiting_ : control_) = job;
}

void FlightComputer::set_running_control_cycles(std::int64_t cycles) {
  if (control_ && control_->started) control_->remaining_ns = duration_ns(cycles);
}

void FlightComputer::request_refit(std::int64_t points) {
  refits_.push_back(Job{now_ns_, duration_ns(settings_.refit_cycles_per_point * points)});
}

void FlightComputer::release_background() {
  for (std::size_t k = 0; k < background_.size(); ++k) {
    Periodic& p = background_[k];
    while (p.next_release_ns <= now_ns_) {
      ++stats_.background_released;
      if (p.job)
        ++stats_.background_skipped;
      else
        p.job = Job{p.next_release_ns, duration_ns(settings_.background[k].cycles)};
      p.next_release_ns += p.period_ns;
    }
  }
}

SimTime FlightComputer::next_background_release() const {
  SimTime next = kNever;
  for (const Periodic& p : background_) next = std::min(next, p.next_release_ns);
  return next;
}

// Fixed priority: drivers > control > refit > background (file order among background tasks).
// A background job already begun holds off control when control may not preempt it.
FlightComputer::Pick FlightComputer::pick(std::size_t& background_index) {
  if (!drivers_.empty()) return Pick::driver;
  std::optional<std::size_t> begun, ready;
  for (std::size_t k = 0; k < background_.size(); ++k) {
    if (!background_[k].job) continue;
    if (!ready) ready = k;
    if (!begun && background_[k].job->started) begun = k;
  }
  if (control_) {
    if (!begun || settings_.control_preempts_background) return Pick::control;
    background_index = *begun;
    return Pick::background;
  }
  if (!refits_.empty()) return Pick::refit;
  if (!ready) return Pick::none;
  background_index = *ready;
  return Pick::background;
}

std::optional<ComputerEvent> FlightComputer::advance(SimTime t_ns) {
  while (true) {
    release_background();
    std::size_t bg = 0;
    const Pick chosen = pick(bg);
    if (chosen == Pick::control && !control_->started) {
      control_->started = true;
      return ComputerEvent{ComputerEvent::Type::control_start, now_ns_, control_->request_ns,
                           control_->cause, control_->merged};
    }
    if (now_ns_ >= t_ns) return std::nullopt;
    const SimTime horizon = std::min(t_ns, next_background_release());
    if (chosen == Pick::none) {
      now_ns_ = horizon;
      continue;
    }
    Job& job = chosen == Pick::driver    ? drivers_.front()
               : chosen == Pick::control ? *control_
               : chosen == Pick::refit   ? refits_.front()
                                         : *background_[bg].job;
    job.started = true;
    const SimTime run = std::min(job.remaining_ns, horizon - now_ns_);
    job.remaining_ns -= run;
    now_ns_ += run;
    stats_.busy_ns += run;
    if (job.remaining_ns > 0) continue;
    switch (chosen) {
      case Pick::driver:
        drivers_.pop_front();
        ++stats_.driver_jobs;
        break;
      case Pick::control: {
        const ComputerEvent end{ComputerEvent::Type::control_end, now_ns_, control_->request_ns,
                                control_->cause, control_->merged};
        control_ = control_waiting_;
        control_waiting_.reset();
        ++stats_.executions;
        return end;
      }
      case Pick::refit: {
        const ComputerEvent end{ComputerEvent::Type::refit_end, now_ns_, refits_.front().request_ns,
                                ReleaseCause::time_triggered, 0};
        refits_.pop_front();
        ++stats_.refits;
        return end;
      }
      case Pick::background: {
        const SimTime latency = now_ns_ - background_[bg].job->request_ns;
        stats_.background_latency_sum_ns += latency;
        stats_.background_latency_max_ns = std::max(stats_.background_latency_max_ns, latency);
        background_[bg].job.reset();
        ++stats_.background_completed;
        break;
      }
      case Pick::none:
        break;
    }
  }
}

}  // namespace swath::control
