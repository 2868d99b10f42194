// The reactive scheduler (docs/swath-control.md) in scripted cases: executions happen at once when
// released, sensor values are chosen by the test. x* = 0 runs at every trigger sample, x* = ∞ only
// at the failsafe, triggers are batched at the hyperperiod and never held beyond max_wait_s, each
// feedback rule adds what it says to the data set.
#include <gtest/gtest.h>

#include "swath/control/reactive_scheduler.hpp"

namespace swath::control {
namespace {

constexpr SimTime kMillisecond = 1'000'000;

ReactiveSettings settings_with(double beta1, double beta2) {
  ReactiveSettings r;
  r.boot_s = 0;
  r.failsafe_s = 0.1;
  r.initial_models = {{"gyro", beta1, beta2}};
  return r;
}

struct Script {
  ReactiveScheduler scheduler;
  std::vector<std::pair<SimTime, ReleaseCause>> releases;

  // Runs to `end`: gyro samples every 1 ms with value `value(t)`; any release executes at once,
  // its output changed as `changed(t)` says.
  template <typename Value, typename Changed>
  void run(SimTime end, Value value, Changed changed) {
    for (SimTime t = 0; t <= end; t += kMillisecond) {
      release_until(t, changed);
      SensorSample s;
      s.time_ns = t;
      s.sensor = 0;
      s.axes = 3;
      s.value = {value(t), 0, 0};
      scheduler.on_sample(s);
      release_until(t, changed);
    }
  }
  template <typename Changed>
  void release_until(SimTime t, Changed changed) {
    while (scheduler.next_release_ns() <= t) {
      const SimTime at = scheduler.next_release_ns();
      releases.push_back({at, scheduler.take_release()});
      scheduler.on_execution_start(at);
      scheduler.on_execution_end(at, changed(at));
    }
  }
};

TEST(Reactive, ThresholdZeroRunsAtEveryTriggerSample) {
  // β = (10, 1): L(0) > 0.6, so x* = 0: every change fires.
  Script s{ReactiveScheduler(settings_with(10, 1), {{"gyro", 0, kMillisecond}}, 400), {}};
  s.run(
      300 * kMillisecond, [](SimTime t) { return static_cast<double>(t % 7); },
      [](SimTime) { return true; });
  // The watchdog's execution at 0 comes before any sample, so the change has a reference only
  // from the next one, at 100 ms; from then on every sample (its value always moves: t mod 7 with
  // t in ns steps by 1) fires an execution at its own instant (H = the 1 ms period).
  std::vector<SimTime> triggered;
  for (const auto& [t, cause] : s.releases)
    if (cause == ReleaseCause::trigger) triggered.push_back(t);
  ASSERT_EQ(triggered.size(), 201u);
  for (std::size_t k = 0; k < triggered.size(); ++k)
    EXPECT_EQ(triggered[k], (100 + static_cast<SimTime>(k)) * kMillisecond);
  EXPECT_EQ(s.releases.front().second, ReleaseCause::failsafe);
}

TEST(Reactive, ThresholdInfinityRunsOnlyAtTheFailsafe) {
  Script s{ReactiveScheduler(settings_with(-10, 0), {{"gyro", 0, kMillisecond}}, 400), {}};
  s.run(
      1000 * kMillisecond, [](SimTime t) { return static_cast<double>(t % 7); },
      [](SimTime) { return false; });
  ASSERT_EQ(s.releases.size(), 11u);  // at 0, 100, ..., 1000 ms
  for (std::size_t k = 0; k < s.releases.size(); ++k) {
    EXPECT_EQ(s.releases[k].first, static_cast<SimTime>(k) * 100 * kMillisecond);
    EXPECT_EQ(s.releases[k].second, ReleaseCause::failsafe);
  }
}

TEST(Reactive, TriggersWaitForTheHyperperiodButNeverBeyondMaxWait) {
  // Periods of 1 ms and 2.5 ms (both ≥ 400 Hz): H = 5 ms; max_wait 2.5 ms.
  ReactiveSettings r = settings_with(10, 1);
  ReactiveScheduler sched(r, {{"gyro", 0, kMillisecond}, {"accel", 1, 2'500'000}}, 400);
  EXPECT_EQ(sched.hyperperiod_ns(), 5 * kMillisecond);
  sched.take_release();  // the watchdog at 0
  sched.on_execution_start(0);
  sched.on_execution_end(0, true);
  SensorSample s;
  s.sensor = 0;
  s.axes = 1;
  s.time_ns = 1 * kMillisecond;
  s.value = {1};
  sched.on_sample(s);  // the first sample of gyro: no reference yet
  EXPECT_EQ(sched.next_release_ns(), 100 * kMillisecond);
  sched.on_execution_start(1 * kMillisecond);  // (an execution takes the reference)
  sched.on_execution_end(1 * kMillisecond, true);
  s.time_ns = 6 * kMillisecond;
  s.value = {2};
  sched.on_sample(s);  // fires at 6 ms: H boundary 10 ms, cap 8.5 ms
  EXPECT_EQ(sched.next_release_ns(), 8'500'000);
  s.time_ns =
      9 * kMillisecond + 1;  // after the release was taken, fires again: boundary 10 ms first
  sched.take_release();
  sched.on_execution_start(8'500'000);
  sched.on_execution_end(8'500'000, true);
  s.value = {3};
  sched.on_sample(s);
  EXPECT_EQ(sched.next_release_ns(), 10 * kMillisecond);
  // With min_rate 0 (the literal paper) a 10 Hz sensor makes H 100 ms, so the cap decides.
  r.accumulation_min_rate_hz = 0;
  ReactiveScheduler literal(r, {{"gyro", 0, kMillisecond}, {"gps", 1, 100 * kMillisecond}}, 400);
  EXPECT_EQ(literal.hyperperiod_ns(), 100 * kMillisecond);
}

// Points in the data set after a flight whose executions leave the output as `changed` says.
std::int64_t points_after(FeedbackRule rule, bool changed, double beta1) {
  ReactiveSettings r = settings_with(beta1, beta1 > 0 ? 1 : 0);
  r.fit_feedback = rule;
  Script s{ReactiveScheduler(r, {{"gyro", 0, kMillisecond}}, 400), {}};
  s.run(
      500 * kMillisecond, [](SimTime t) { return static_cast<double>(t % 7); },
      [changed](SimTime) { return changed; });
  return s.scheduler.begin_refit(500 * kMillisecond);
}

TEST(Reactive, FeedbackRulesAddWhatTheySay) {
  // Always firing (β1 = 10): a single-trigger execution at every sample from 100 ms (the first
  // with a reference, see above) to 500 ms: 401. Unchanged → false positives. The watchdog's
  // execution at 100 ms, if it changes the output, is a false negative: 1.
  EXPECT_EQ(points_after(FeedbackRule::errors, false, 10), 401);
  EXPECT_EQ(points_after(FeedbackRule::errors, true, 10), 1);  // true positives: not in `errors`
  EXPECT_EQ(points_after(FeedbackRule::all, true, 10), 402);
  EXPECT_EQ(points_after(FeedbackRule::none, false, 10), 0);
  // Never firing: failsafe executions every 100 ms; changed → false negatives (the one at 0 has
  // no sample before it).
  EXPECT_EQ(points_after(FeedbackRule::errors, true, -10), 5);
  EXPECT_EQ(points_after(FeedbackRule::errors, false, -10), 0);
}

TEST(Reactive, AModelWithoutAPositiveSlopeNeverFiresAtZeroChange) {
  // β = (10, −1): L(0) > P_run and L falls with x, crossing P_run at x = 9.6. A sensor that does
  // not change (x = 0) must not fire on every sample; one that changes by 1 fires; by 20, not.
  Script s{ReactiveScheduler(settings_with(10, -1), {{"gyro", 0, kMillisecond}}, 400), {}};
  auto value = [](SimTime t) {
    const auto ms = static_cast<double>(t / kMillisecond);
    return ms < 300 ? 300.0 : ms < 600 ? ms : 600 + 20 * (ms - 600);
  };
  s.run(1000 * kMillisecond, value, [](SimTime) { return true; });
  int quiet = 0, small = 0, large = 0;
  for (const auto& [t, cause] : s.releases) {
    if (cause != ReleaseCause::trigger) {
      EXPECT_EQ(cause, ReleaseCause::failsafe);
      continue;
    }
    ++(t < 300 * kMillisecond ? quiet : t <= 600 * kMillisecond ? small : large);
  }
  EXPECT_EQ(quiet, 0);
  EXPECT_EQ(small, 300);  // every sample from 301 ms to 600 ms
  EXPECT_EQ(large, 0);
}

// Two trigger sensors driven by hand: a 1 kHz gyro and a 10 Hz GPS (sensor 1).
struct TwoSensors {
  ReactiveScheduler scheduler;
  std::vector<std::pair<SimTime, ReleaseCause>> releases;
  std::vector<std::uint64_t> trigger_sets;
  // Samples of one instant are all delivered before the releases of that instant run.
  void sample(std::size_t sensor, SimTime t, double value) {
    SensorSample s;
    s.time_ns = t;
    s.sensor = sensor;
    s.axes = 1;
    s.value = {value};
    scheduler.on_sample(s);
  }
  void release_until(SimTime t) {
    while (scheduler.next_release_ns() <= t) {
      const SimTime at = scheduler.next_release_ns();
      releases.push_back({at, scheduler.take_release()});
      scheduler.on_execution_start(at);
      scheduler.on_execution_end(at, false);
      trigger_sets.push_back(scheduler.last_execution().trigger_sensors);
    }
  }
};

TEST(Reactive, ASlowSensorFiringOnEveryFixDoesNotHoldOffTheFailsafe) {
  // The GPS fires on every fix (L(x) > P_run for all x > 0), 10 Hz = the failsafe's period with a
  // phase of 50 ms; the gyro never changes. Its executions must not reset the watchdog: the
  // failsafe still runs every 100 ms from the last one of its own.
  ReactiveSettings r = settings_with(-10, 1);
  r.initial_models.push_back({"gps", 10, 1});
  TwoSensors two{
      ReactiveScheduler(r, {{"gyro", 0, kMillisecond}, {"gps", 1, 100 * kMillisecond}}, 400),
      {},
      {}};
  for (SimTime t = 0; t <= 1000 * kMillisecond; t += kMillisecond) {
    two.release_until(t);
    two.sample(0, t, 0.0);
    if (t % (100 * kMillisecond) == 50 * kMillisecond) two.sample(1, t, static_cast<double>(t));
    two.release_until(t);
  }
  int failsafes = 0, gps = 0;
  for (const auto& [t, cause] : two.releases) {
    if (cause == ReleaseCause::failsafe) {
      ++failsafes;
      EXPECT_EQ(t % (100 * kMillisecond), 0) << t;
    }
    if (cause == ReleaseCause::trigger) ++gps;
  }
  EXPECT_EQ(failsafes, 11);
  EXPECT_EQ(gps, 9);  // from 150 ms: the first fix has no reference
}

TEST(Reactive, SimultaneousTriggersAreAttributedToEverySensorThatFired) {
  // Gyro and accelerometer sample together and both always fire: with `all` each execution gives
  // each of them a point; the paper's `errors` rule excludes every one of them (several causes).
  for (const FeedbackRule rule : {FeedbackRule::all, FeedbackRule::errors}) {
    ReactiveSettings r = settings_with(10, 1);
    r.initial_models.push_back({"accel", 10, 1});
    r.fit_feedback = rule;
    TwoSensors two{
        ReactiveScheduler(r, {{"gyro", 0, kMillisecond}, {"accel", 1, kMillisecond}}, 400), {}, {}};
    for (SimTime t = 0; t <= 200 * kMillisecond; t += kMillisecond) {
      two.release_until(t);
      two.sample(0, t, static_cast<double>(t / kMillisecond));
      two.sample(1, t, static_cast<double>(t / kMillisecond));
      two.release_until(t);
    }
    std::int64_t both = 0;
    for (std::size_t k = 0; k < two.releases.size(); ++k)
      if (two.releases[k].second == ReleaseCause::trigger) {
        EXPECT_EQ(two.trigger_sets[k], 3u);
        ++both;
      }
    // Every instant from 100 ms, when the failsafe's execution gave both sensors a reference.
    EXPECT_EQ(both, 101);
    const std::int64_t points = two.scheduler.begin_refit(200 * kMillisecond);
    if (rule == FeedbackRule::all) {
      EXPECT_EQ(points, 2 * both + 2);  // and the failsafe at 100 ms, both sensors fresh
      EXPECT_EQ(two.scheduler.feedback().false_positives, both);
    } else {
      EXPECT_EQ(points, 0);  // the failsafe did not change the output: no false negative
      EXPECT_EQ(two.scheduler.feedback().multi_cause_excluded, both);
    }
  }
}

TEST(Reactive, TheBootRunsTimeTriggeredAndFitsWhenItEnds) {
  ReactiveSettings r;
  r.boot_s = 0.5;
  r.boot_rate_hz = 100;
  ReactiveScheduler sched(r, {{"gyro", 0, kMillisecond}}, 400);
  Script s{sched, {}};
  s.run(
      499 * kMillisecond, [](SimTime t) { return static_cast<double>(t % 7); },
      [](SimTime t) { return t % 20'000'000 == 0; });
  ASSERT_EQ(s.releases.size(), 50u);  // 100 Hz for 0.5 s
  for (const auto& [t, cause] : s.releases) EXPECT_EQ(cause, ReleaseCause::boot);
  EXPECT_EQ(s.scheduler.next_refit_ns(), 500 * kMillisecond);
  // Each boot execution after the first (at 0, before any sample) saw gyro samples: 49 points.
  EXPECT_EQ(s.scheduler.begin_refit(500 * kMillisecond), 49);
  s.scheduler.end_refit(510 * kMillisecond);
  EXPECT_EQ(s.scheduler.stats()[0].refits, 1);
  EXPECT_EQ(s.scheduler.next_refit_ns(), 1510 * kMillisecond);
}

}  // namespace
}  // namespace swath::control
