// The flight computer and the TT scheduler (docs/swath-control.md; CPU overruns and energy):
// scripted timelines whose busy time, start and end instants,
// overruns and energy are worked out by hand or by an independent formula.

#include <gtest/gtest.h>

#include <vector>

#include "swath/control/computer.hpp"
#include "swath/vehicle/random.hpp"

namespace swath::control {
namespace {

constexpr SimTime kMs = 1'000'000, kUs = 1'000;

ComputerSettings bare(std::int64_t control_cycles) {
  ComputerSettings s;
  s.clock_hz = 100e6;  // 10 ns per cycle: durations come out whole
  s.control_cycles = control_cycles;
  s.driver_cycles = 1'500;  // 15 µs
  s.background.clear();
  return s;
}

struct Timeline {
  std::vector<ComputerEvent> starts, ends;
  int releases = 0;
};

// Drives the core to `end_ns` with sensor samples every `sample_ns` (0: none) and the TT
// scheduler's releases; at one instant samples come before the release (docs/swath-control.md,
// 'The simulated multirotor', its clock).
Timeline run(FlightComputer& cpu, TimeTriggeredScheduler& tt, SimTime sample_ns, SimTime end_ns) {
  Timeline tl;
  auto drain = [&](SimTime t) {
    while (const auto e = cpu.advance(t))
      (e->type == ComputerEvent::Type::control_start ? tl.starts : tl.ends).push_back(*e);
  };
  SimTime next_sample = sample_ns > 0 ? 0 : kNever;
  while (true) {
    const SimTime t = std::min(next_sample, tt.next_release_ns());
    if (t >= end_ns) break;
    drain(t);
    if (t == next_sample) {
      cpu.sample();
      next_sample += sample_ns;
    }
    if (t == tt.next_release_ns()) {
      cpu.request_control(tt.take_release());
      ++tl.releases;
    }
  }
  drain(end_ns);
  return tl;
}

TEST(Computer, Tt400WithDriversHasExactBusyTimeLatencyAndEnergy) {
  const ComputerSettings s = bare(100'000);  // 1 ms per execution
  FlightComputer cpu(s);
  TimeTriggeredScheduler tt = *TimeTriggeredScheduler::at_rate(400);
  const Timeline tl = run(cpu, tt, kMs, 1000 * kMs);
  ASSERT_EQ(tl.releases, 400);
  ASSERT_EQ(tl.starts.size(), 400u);
  ASSERT_EQ(tl.ends.size(), 400u);
  for (std::size_t k = 0; k < 400; ++k) {
    // A release on a whole millisecond waits for that sample's driver (15 µs); each sample
    // falling inside the execution preempts it for another 15 µs.
    const SimTime release = static_cast<SimTime>(k) * 2'500 * kUs;
    const SimTime start = release + (release % kMs == 0 ? 15 * kUs : 0);
    SimTime end = start + kMs;
    for (SimTime sample = (start / kMs + 1) * kMs; sample < end; sample += kMs) end += 15 * kUs;
    EXPECT_EQ(tl.starts[k].request_ns, release);
    EXPECT_EQ(tl.starts[k].time_ns, start) << k;
    EXPECT_EQ(tl.ends[k].time_ns, end) << k;
  }
  EXPECT_EQ(cpu.stats().busy_ns, 400 * kMs + 1000 * 15 * kUs);
  EXPECT_EQ(cpu.stats().overruns, 0);
  EXPECT_EQ(cpu.stats().driver_jobs, 1000);
  // P_cpu = idle + (active − idle) · busy over 1 s: 0.15 + 0.25 · 0.415.
  EXPECT_NEAR(cpu.energy_j(), 0.15 + 0.25 * 0.415, 1e-12);
}

TEST(Computer, MissedReleasesAreOverruns) {
  // 3 ms executions released every 2.5 ms: one request waits while one runs; at 17.5 ms a release
  // finds the 15-ms one still waiting and joins it (worked out by hand).
  FlightComputer cpu(bare(300'000));
  TimeTriggeredScheduler tt = *TimeTriggeredScheduler::at_rate(400);
  const Timeline tl = run(cpu, tt, 0, 30 * kMs);
  const std::vector<SimTime> expected_starts{0, 3, 6, 9, 12, 15, 18, 21, 24, 27, 30};
  ASSERT_EQ(tl.starts.size(), expected_starts.size());
  for (std::size_t k = 0; k < expected_starts.size(); ++k)
    EXPECT_EQ(tl.starts[k].time_ns, expected_starts[k] * kMs) << k;
  EXPECT_EQ(tl.starts[6].request_ns, 15 * kMs);
  EXPECT_EQ(tl.starts[6].merged, 1);
  EXPECT_EQ(tl.starts[7].request_ns, 20 * kMs);
  EXPECT_EQ(cpu.stats().overruns, 1);
  EXPECT_EQ(cpu.stats().executions, 10);  // the one begun at 27 ms ends at 30 ms
  // Every release is accounted for: executed, begun at 30 ms (the 27.5-ms one), or merged as an
  // overrun.
  EXPECT_EQ(tl.releases, cpu.stats().executions + 1 + cpu.stats().overruns);
  EXPECT_TRUE(cpu.control_pending());
  EXPECT_EQ(cpu.stats().busy_ns, 30 * kMs);
  EXPECT_NEAR(cpu.energy_j(), 0.40 * 0.030, 1e-15);  // busy all along: active power
}

TEST(Computer, ControlPreemptsBackgroundUnlessToldNotTo) {
  for (const bool preempt : {true, false}) {
    ComputerSettings s = bare(100'000);
    s.background = {{"logging", 10, 500'000}};  // 5 ms at 0, 100 ms, …
    s.control_preempts_background = preempt;
    FlightComputer cpu(s);
    TimeTriggeredScheduler tt(10 * kMs, kMs);  // 100 Hz from 1 ms
    const Timeline tl = run(cpu, tt, 0, 200 * kMs);
    ASSERT_EQ(tl.starts.size(), 20u);
    // The release at 1 ms meets the logging job begun at 0: at once when control preempts, at
    // its end (5 ms) when not, and the logging job then ends at 6 ms or 5 ms.
    EXPECT_EQ(tl.starts[0].time_ns, preempt ? 1 * kMs : 5 * kMs);
    EXPECT_EQ(tl.ends[0].time_ns, preempt ? 2 * kMs : 6 * kMs);
    EXPECT_EQ(tl.starts[10].time_ns, preempt ? 101 * kMs : 105 * kMs);
    EXPECT_EQ(tl.starts[1].time_ns, 11 * kMs);
    EXPECT_EQ(cpu.stats().busy_ns, 2 * 5 * kMs + 20 * kMs);
    EXPECT_EQ(cpu.stats().background_completed, 2);
    // Release to completion: 5 ms of work, plus the 1 ms of control that preempted it.
    EXPECT_EQ(cpu.stats().background_released, 3);  // 0, 100 and 200 ms (not yet run)
    EXPECT_EQ(cpu.stats().background_latency_max_ns, preempt ? 6 * kMs : 5 * kMs);
    EXPECT_EQ(cpu.stats().background_latency_sum_ns, preempt ? 12 * kMs : 10 * kMs);
  }
}

TEST(Computer, BackgroundReleasesThatFindTheirJobUnfinishedAreSkipped) {
  ComputerSettings s = bare(0);
  s.background = {{"slow", 1000, 200'000}};  // 2 ms of work every 1 ms
  FlightComputer cpu(s);
  while (cpu.advance(10 * kMs)) {
  }
  EXPECT_EQ(cpu.stats().background_completed, 5);
  EXPECT_EQ(cpu.stats().background_skipped, 5);
  EXPECT_EQ(cpu.stats().busy_ns, 10 * kMs);
}

TEST(Computer, RefitsRunBelowControlAndAboveBackground) {
  ComputerSettings s = bare(100'000);
  s.refit_cycles_per_point = 100;         // 1 µs per point
  s.background = {{"bg", 1, 1'000'000}};  // 10 ms from 0
  FlightComputer cpu(s);
  ASSERT_FALSE(cpu.advance(kMs));  // background runs 0..1 ms so far
  cpu.request_refit(2'000);        // 2 ms
  cpu.request_control(ReleaseCause::time_triggered);
  std::vector<ComputerEvent> events;
  while (const auto e = cpu.advance(20 * kMs)) events.push_back(*e);
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].type, ComputerEvent::Type::control_start);
  EXPECT_EQ(events[0].time_ns, kMs);
  EXPECT_EQ(events[1].type, ComputerEvent::Type::control_end);
  EXPECT_EQ(events[1].time_ns, 2 * kMs);
  EXPECT_EQ(events[2].type, ComputerEvent::Type::refit_end);
  EXPECT_EQ(events[2].time_ns, 4 * kMs);
  EXPECT_EQ(cpu.stats().busy_ns, 13 * kMs);  // background's 10 ms end at 13 ms
}

TEST(Computer, RandomTimelinesConserveWorkAndReleases) {
  // Whatever the rates and costs: once releases stop and the core has caught up, the busy time is
  // exactly the work submitted, and every release was executed or merged as an overrun.
  vehicle::SplitMix64 rng(2016);
  const double rates_hz[] = {100, 200, 250, 400, 500, 1000};
  for (int trial = 0; trial < 40; ++trial) {
    ComputerSettings s = bare(static_cast<std::int64_t>(rng.below(400'000)));
    s.clock_hz = 50e6 + static_cast<double>(rng.below(150)) * 1e6;
    s.driver_cycles = static_cast<std::int64_t>(rng.below(5'000));
    FlightComputer cpu(s);
    TimeTriggeredScheduler tt = *TimeTriggeredScheduler::at_rate(rates_hz[rng.below(6)]);
    const SimTime sample_ns = static_cast<SimTime>(1 + rng.below(4)) * 500 * kUs;
    const Timeline tl = run(cpu, tt, sample_ns, 300 * kMs);
    while (cpu.advance(10'000 * kMs)) {
    }
    const ComputerStats& st = cpu.stats();
    EXPECT_FALSE(cpu.control_pending());
    EXPECT_EQ(tl.releases, st.executions + st.overruns) << trial;
    EXPECT_EQ(st.busy_ns, st.driver_jobs * cpu.duration_ns(s.driver_cycles) +
                              st.executions * cpu.duration_ns(s.control_cycles))
        << trial;
    EXPECT_EQ(st.driver_jobs, (300 * kMs + sample_ns - 1) / sample_ns);
    // Each execution starts no earlier than its request and ends at least its cost later.
    for (std::size_t k = 0; k < tl.ends.size(); ++k) {
      EXPECT_GE(tl.starts[k].time_ns, tl.starts[k].request_ns);
      EXPECT_GE(tl.ends[k].time_ns - tl.starts[k].time_ns, cpu.duration_ns(s.control_cycles));
    }
  }
}

TEST(Computer, CyclesRoundUpToWholeNanoseconds) {
  ComputerSettings s;
  s.clock_hz = 168e6;
  const FlightComputer cpu(s);
  EXPECT_EQ(cpu.duration_ns(120'000), 714'286);  // 714,285.71 ns
  EXPECT_EQ(cpu.duration_ns(168), 1'000);
  EXPECT_EQ(cpu.duration_ns(0), 0);
}

TEST(Scheduler, TimeTriggeredReleasesOnItsGrid) {
  TimeTriggeredScheduler tt = *TimeTriggeredScheduler::at_rate(400, 123);
  for (SimTime k = 0; k < 1000; ++k) {
    EXPECT_EQ(tt.next_release_ns(), 123 + k * 2'500'000);
    tt.on_sample(SensorSample{});  // events change nothing
    EXPECT_EQ(tt.take_release(), ReleaseCause::time_triggered);
  }
  EXPECT_FALSE(TimeTriggeredScheduler::at_rate(300).has_value());  // 3,333,333.3 ns
  EXPECT_FALSE(TimeTriggeredScheduler::at_rate(0).has_value());
}

}  // namespace
}  // namespace swath::control
