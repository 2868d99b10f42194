// The reactive scheduler (docs/swath-control.md) in scripted cases: executions happen at once when
// released, sensor values are chosen by the test. x* = 0 runs at every trigger sample, x* = ∞ only
// at the failsafe, triggers are batched at the hyperperiod and never held beyond max_wait_s, each
// feedback rule adds what it says to the data set.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <deque>
#include <utility>

#include "swath/control/reactive_scheduler.hpp"
#include "swath/vehicle/random.hpp"

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

// Each refit fits the last fit.dataset_capacity points fed back, as fit_logistic fits them in
// the order they came (the scheduler keeps them sorted between refits and merges in what was
// added and dropped): the same bits at every refit, for both grouped-logit methods.
TEST(Reactive, RefitsFitTheLastPointsFedBackToTheBit) {
  for (const FitMethod method : {FitMethod::logit_ols, FitMethod::logit_wls}) {
    ReactiveSettings r = settings_with(10, 0);  // fires at every change until the first refit
    r.failsafe_s = 10;                          // no failsafe executions: trigger points only
    r.p_run = 0.05;  // random labels fit L ≈ 0.5 everywhere: still firing at every change
    r.fit_method = method;
    r.fit_refit_period_s = 0.05;
    r.fit_dataset_capacity = 300;
    r.fit_min_per_bin = 10;
    ReactiveScheduler sched(r, {{"gyro", 0, kMillisecond}}, 400);
    auto random = vehicle::SplitMix64::stream(3, "refits");
    std::deque<TriggerPoint> expected;  // the points fed back, the last 300
    int refits = 0;
    for (SimTime t = 0; t <= 3000 * kMillisecond; t += kMillisecond) {
      if (sched.next_refit_ns() <= t) {
        ASSERT_EQ(sched.begin_refit(t), static_cast<std::int64_t>(expected.size()));
        sched.end_refit(t);
        const std::vector<TriggerPoint> data(expected.begin(), expected.end());
        const LogisticModel m = fit_logistic(data, method, r.fit_bins, r.fit_min_per_bin);
        const TriggerStats& st = sched.stats()[0];
        EXPECT_EQ(st.dataset, data.size());
        EXPECT_EQ(std::bit_cast<std::uint64_t>(st.model.beta1),
                  std::bit_cast<std::uint64_t>(m.beta1))
            << t;
        EXPECT_EQ(std::bit_cast<std::uint64_t>(st.model.beta2),
                  std::bit_cast<std::uint64_t>(m.beta2))
            << t;
        ++refits;
      }
      SensorSample s;
      s.time_ns = t;
      s.sensor = 0;
      s.axes = 3;
      s.value = {static_cast<double>(random.below(8)) * 0.5, 0, 0};  // changes with many ties
      sched.on_sample(s);
      bool new_sample = true;
      while (sched.next_release_ns() <= t) {
        const SimTime at = sched.next_release_ns();
        sched.take_release();
        sched.on_execution_start(at);
        const bool saw_sample = std::exchange(new_sample, false);
        const bool changed = random.uniform() < 0.5;
        sched.on_execution_end(at, changed);
        const ExecutionRecord& e = sched.last_execution();
        // A trigger's execution, or the failsafe's after a new sample (the first, at 0): a point.
        if ((e.causes == 4 && (e.trigger_sensors & 1)) || (e.causes == 8 && saw_sample)) {
          expected.push_back({e.x[0], changed});
          if (expected.size() > 300) expected.pop_front();
        }
      }
    }
    EXPECT_GT(refits, 50);
    EXPECT_EQ(expected.size(), 300u);
  }
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

TEST(Reactive, AHigherPRunNeverTriggersMoreOnTheSameSamples) {
  // The trigger rule L(x) ≥ P_run is monotone in P_run: on the same samples, each sample that
  // fires at a higher P_run fires at every lower one. With the change measured from the previous
  // sample (delta_reference last_sample) and the models frozen (feedback none), x does not depend
  // on when the loop ran, so the samples that fire at P_run q ⊆ those at p < q, and the trigger
  // executions are at most as many.
  std::vector<std::vector<SimTime>> fired;
  std::vector<std::size_t> executions;
  const std::vector<double> p_runs{0.05, 0.2, 0.35, 0.5, 0.6, 0.65, 0.8, 0.95};
  for (const double p : p_runs) {
    ReactiveSettings r = settings_with(-3, 2);  // L = 1/2 at x = 1.5
    r.p_run = p;
    r.delta_reference = DeltaReference::last_sample;
    r.fit_feedback = FeedbackRule::none;
    Script s{ReactiveScheduler(r, {{"gyro", 0, kMillisecond}}, 400), {}};
    std::uint64_t state = 2024;  // a fixed seed: x ~ |U(-3, 3)| between samples
    double value = 0;
    std::vector<SimTime> mine;
    std::int64_t seen = 0;
    for (SimTime t = 0; t <= 2000 * kMillisecond; t += kMillisecond) {
      s.release_until(t, [](SimTime) { return true; });
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      value += 6.0 * (static_cast<double>(state >> 11) * 0x1.0p-53 - 0.5);
      SensorSample sample;
      sample.time_ns = t;
      sample.axes = 1;
      sample.value = {value};
      s.scheduler.on_sample(sample);
      if (s.scheduler.stats()[0].triggers != seen) mine.push_back(t);
      seen = s.scheduler.stats()[0].triggers;
    }
    std::size_t triggered = 0;
    for (const auto& [t, cause] : s.releases) triggered += cause == ReleaseCause::trigger;
    fired.push_back(mine);
    executions.push_back(triggered);
  }
  for (std::size_t k = 1; k < p_runs.size(); ++k) {
    EXPECT_LE(executions[k], executions[k - 1]) << "P_run " << p_runs[k];
    EXPECT_TRUE(
        std::includes(fired[k - 1].begin(), fired[k - 1].end(), fired[k].begin(), fired[k].end()))
        << "P_run " << p_runs[k];
  }
  // P_run acts here: x > x* = (logit P_run + 3) / 2 with |Δ| uniform on [0, 3] fires for
  // 1 − x*/3 of the samples (0.05: 0.99, 0.95: 0.01) from the first failsafe execution at 100 ms,
  // which gives the change its first reference: 1,901 samples.
  EXPECT_NEAR(static_cast<double>(fired.front().size()) / 1901, 1 - (std::log(0.05 / 0.95) + 3) / 6,
              0.03);
  EXPECT_NEAR(static_cast<double>(fired.back().size()) / 1901, 1 - (std::log(0.95 / 0.05) + 3) / 6,
              0.03);
}

// Which nodes a change reaches, found without the graph's order: grow the set until no node
// reading a member (or a changed input) is left out.
std::uint32_t reached(unsigned inputs) {
  const auto graph = control_graph();
  std::uint32_t set = 0;
  for (bool grew = true; grew;) {
    grew = false;
    for (std::size_t j = 0; j < graph.size(); ++j) {
      const bool reads = (graph[j].inputs & inputs) || (graph[j].upstream & set);
      if (reads && !(set >> j & 1)) {
        set |= 1u << j;
        grew = true;
      }
    }
  }
  return set;
}

TEST(ControlGraph, AnExecutionRunsTheNodesDownstreamOfWhatChanged) {
  const auto graph = control_graph();
  ASSERT_EQ(graph.size(), 7u);  // the seven steps of ControlTask::execute
  for (unsigned inputs = 0; inputs < 1u << kGraphInputs; ++inputs)
    EXPECT_EQ(nodes_to_run(inputs), reached(inputs)) << "inputs " << inputs;
  EXPECT_EQ(nodes_to_run((1u << kGraphInputs) - 1), whole_graph());
  // Every node is downstream of something, and the mixer of everything.
  for (unsigned i = 0; i < kGraphInputs; ++i) EXPECT_TRUE(nodes_to_run(1u << i) >> 6 & 1) << i;
  // The attitude filter feeds every later step, so what reaches it reaches the whole graph; the
  // baro and the position fix enter at the position filter, a new leg at position control.
  const auto in = [](GraphInput i) { return 1u << static_cast<unsigned>(i); };
  for (GraphInput i : {GraphInput::gyro, GraphInput::accel, GraphInput::mag})
    EXPECT_EQ(nodes_to_run(in(i)), whole_graph());
  EXPECT_EQ(nodes_to_run(in(GraphInput::baro)), whole_graph() & ~1u);
  EXPECT_EQ(nodes_to_run(in(GraphInput::setpoint)), whole_graph() & ~3u);
}

TEST(ControlGraph, TheNodesCyclesAddUpToTheTask) {
  double shares = 0;
  for (const GraphNode& n : control_graph()) shares += n.share;
  EXPECT_NEAR(shares, 1.0, 1e-12);
  for (const std::int64_t whole : {std::int64_t{120'000}, std::int64_t{7}, std::int64_t{0}}) {
    EXPECT_EQ(graph_cycles(whole_graph(), whole), whole);
    EXPECT_EQ(graph_cycles(0, whole), 0);
    // Additive over disjoint sets of nodes.
    for (std::uint32_t a = 0; a <= whole_graph(); ++a)
      for (std::uint32_t b = 0; b <= whole_graph(); b += 5)
        if ((a & b) == 0) {
          EXPECT_EQ(graph_cycles(a | b, whole), graph_cycles(a, whole) + graph_cycles(b, whole));
        }
  }
  // Each node costs its share of the task, within a cycle of rounding.
  const auto graph = control_graph();
  for (std::size_t j = 0; j < graph.size(); ++j)
    EXPECT_NEAR(static_cast<double>(graph_cycles(1u << j, 120'000)), graph[j].share * 120'000, 1.0)
        << graph[j].name;
}

}  // namespace
}  // namespace swath::control
