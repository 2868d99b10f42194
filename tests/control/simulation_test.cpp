// The composed flight (control/simulation): the plant, the sensor driver, the flight computer
// running the control task on time-triggered releases, the carrot, the battery. Checked against
// independent truth: release counts on the integer clock, the battery's charge integrated again
// from the rows, energy parts from their own definitions, clearance from geometry, and byte
// determinism for a seed.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <vector>

#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/control/computer.hpp"
#include "swath/control/config.hpp"
#include "swath/control/control_files.hpp"
#include "swath/control/experiment.hpp"
#include "swath/control/mission.hpp"
#include "swath/control/scheduler.hpp"
#include "swath/control/simulation.hpp"
#include "swath/energy/battery.hpp"
#include "swath/energy/guidance.hpp"
#include "swath/energy/plan.hpp"
#include "swath/energy/sim_config.hpp"
#include "swath/vehicle/vehicle_files.hpp"

namespace swath::control {
namespace {

// Every row and second as the files would hold them.
struct Capture : SimulationObserver {
  std::string rows, seconds;
  std::vector<TimeseriesRow> kept;
  std::vector<RateRow> rates;
  void on_row(const TimeseriesRow& r) override {
    rows += timeseries_csv_row(r);
    kept.push_back(r);
  }
  void on_second(const RateRow& r) override {
    seconds += rate_csv_row(r);
    rates.push_back(r);
  }
};

FlightMission line_mission(double length_m, double altitude_m) {
  FlightMission m;
  m.name = "line";
  m.legs.push_back({{0, 0, altitude_m}, {length_m, 0, altitude_m}});
  return m;
}

SimulationSettings short_flight(const FlightMission& mission, const char* environment = "calm") {
  SimulationSettings s;
  s.environment = vehicle::environment_preset(environment);
  s.mission = mission;
  s.speed_m_s = 3.0;
  s.scheduler.run.metrics_from_s = 0;
  s.scheduler.run.max_time_s = 120;
  return s;
}

TEST(Simulation, TimeTriggeredReleasesAreExactlyTheRateAndEveryExecutionReachesTheMotors) {
  SimulationSettings s = short_flight(line_mission(30, 10));
  Capture c;
  const SimulationSummary r = simulate(s, &c);
  ASSERT_EQ(r.status, FlightStatus::completed);
  // Releases at k · 2.5 ms from 0: the executions that ended by the end of the flight.
  const double t = r.flight_time_s;
  const auto released = static_cast<std::int64_t>(std::floor(t / 0.0025)) + 1;
  EXPECT_GE(r.executions.total, released - 1);
  EXPECT_LE(r.executions.total, released);
  EXPECT_EQ(r.executions.by_cause[0], r.executions.total);
  EXPECT_EQ(r.executions.overruns, 0);
  for (const RateRow& row : c.rates) {
    if (row.second > static_cast<int>(t)) continue;  // the last, partial second
    EXPECT_EQ(row.executions, 400) << row.second;
  }
  // The latency is the control task's cycles on the 168 MHz core (120,000 cycles = 0.714 ms)
  // plus the driver jobs that preempt it.
  EXPECT_GE(r.executions.latency_mean_ms, 120'000 / 168e6 * 1e3);
  EXPECT_LT(r.executions.latency_max_ms, 120'000 / 168e6 * 1e3 + 0.1);
}

TEST(Simulation, TheFlightEndsAtTheLastPointAndItsDistanceIsThePath) {
  const SimulationSummary r = simulate(short_flight(line_mission(30, 10)), nullptr);
  ASSERT_EQ(r.status, FlightStatus::completed);
  // 30 m at 3 m/s with 1 m/s² ramps: 13 s for the carrot, and the vehicle within 1 m of the end.
  EXPECT_GE(r.flight_time_s, 13.0);
  EXPECT_LT(r.flight_time_s, 13.0 + 10.0);
  EXPECT_NEAR(r.distance_m, 30.0, 3.0);  // plus the hover's noise
  EXPECT_LT(r.cross_track_m.max, 1.0);
}

TEST(Simulation, TheBatteryChargeIsTheIntegralOfEquation12OverTheRows) {
  SimulationSettings s = short_flight(line_mission(30, 10));
  Capture c;
  const SimulationSummary r = simulate(s, &c);
  EXPECT_LT(r.balance_residual, 1e-9);
  // The parts from their own definitions.
  EXPECT_NEAR(r.avionics_j, s.physics.avionics_w * r.flight_time_s, 1e-6);
  EXPECT_NEAR(r.total_j, r.motors_j + r.cpu_j + r.avionics_j, 1e-6);
  const double busy_share = r.cpu_utilisation;
  const ComputerSettings& cpu = s.control.computer;
  EXPECT_NEAR(r.cpu_j, r.flight_time_s * (cpu.idle_w + (cpu.active_w - cpu.idle_w) * busy_share),
              1e-6 * r.cpu_j);
  // SoC again from the rows' mean powers (20 ms steps instead of 1 ms): eq. 12 is smooth, so the
  // two integrals agree to well under a thousandth of the charge used.
  double soc = s.battery.initial_soc, last_t = 0;
  for (const TimeseriesRow& row : c.kept) {
    const double p = row.motors_w + row.cpu_w + row.avionics_w, dt = row.t_s - last_t;
    soc -= energy::battery_current_a(s.battery, p) * dt / (3600 * s.battery.capacity_ah);
    last_t = row.t_s;
    EXPECT_NEAR(row.soc, soc, 1e-3 * (1 - soc) + 1e-9) << row.t_s;
  }
  // Hover power dominates: about 195 W of motors for a quad-f450 (the closed form), ±15 %.
  const double hover_w = vehicle::hover(s.physics.airframe).motor_power_w;
  EXPECT_NEAR(r.motors_j / r.flight_time_s, hover_w, 0.15 * hover_w);
}

TEST(Simulation, TheSameSeedGivesTheSameBytesAndAnotherSeedOtherBytes) {
  const FlightMission m = line_mission(20, 8);
  auto run = [&](std::uint64_t seed) {
    SimulationSettings s = short_flight(m, "arch");
    s.seed = seed;
    Capture c;
    const SimulationSummary r = simulate(s, &c);
    return c.rows + c.seconds + summary_json(r, {"line", "quad", "tt", "arch", seed, 3, false}, s);
  };
  const std::string a = run(7), b = run(7), other = run(8);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, other);
}

TEST(Simulation, LoopFliesLapsUntilTheReserve) {
  SimulationSettings s = short_flight(closed_for_loop(line_mission(15, 5)));
  s.loop = true;
  s.battery.capacity_ah = 0.15;  // about 2 min of hover to the 20 % reserve
  s.scheduler.run.max_time_s = 600;
  const SimulationSummary r = simulate(s, nullptr);
  ASSERT_EQ(r.status, FlightStatus::reserve_reached);
  ASSERT_TRUE(r.reserve_time_s);
  EXPECT_DOUBLE_EQ(*r.reserve_time_s, r.flight_time_s);
  EXPECT_NEAR(r.final_soc, s.battery.reserve_soc, 1e-3);
  // 15 m there and back at 3 m/s with ramps: 16 s a lap.
  EXPECT_NEAR(r.laps, r.flight_time_s / 16.0, 1.0);
  // Without --loop the same battery flies once and lands well above the reserve.
  s.loop = false;
  s.mission = line_mission(15, 5);
  EXPECT_EQ(simulate(s, nullptr).status, FlightStatus::completed);
}

TEST(Simulation, AnEmptyBatteryAndLostControlAreStatusesNotExceptions) {
  SimulationSettings s = short_flight(line_mission(30, 10));
  s.battery.capacity_ah = 0.002;  // a few seconds
  SimulationSummary r = simulate(s, nullptr);
  EXPECT_EQ(r.status, FlightStatus::battery_empty);
  EXPECT_LT(r.flight_time_s, 13.0);
  EXPECT_LE(r.final_soc, 0.0);

  s = short_flight(line_mission(30, 10), "arch");
  s.control.controller.limits.crash_tilt_deg = 1.0;  // any gust tilts it beyond
  r = simulate(s, nullptr);
  EXPECT_EQ(r.status, FlightStatus::lost_control);
  EXPECT_NE(r.lost_control_reason.find("tilt"), std::string::npos);
}

TEST(Simulation, TheTrackIsCheckedAgainstTheAreaAndNoFlyZones) {
  // A 40 m line along y = 0; a no-fly zone 6 m north of it; an area covering only x <= 20.
  FlightMission m = line_mission(40, 10);
  m.area = {{{-5, -10}, {20, -10}, {20, 10}, {-5, 10}}};
  m.no_fly = {{{10, 6}, {30, 6}, {30, 12}, {10, 12}}};
  const SimulationSummary r = simulate(short_flight(m), nullptr);
  ASSERT_TRUE(r.checked_against_plan);
  ASSERT_TRUE(r.min_clearance_m);
  EXPECT_NEAR(*r.min_clearance_m, 6.0, 0.6);  // the cross-track error stays under 0.6 m
  EXPECT_EQ(r.inside_no_fly_m, 0.0);
  EXPECT_NEAR(r.outside_area_m, 20.0, 1.0);
}

TEST(Simulation, WhatCannotFlyIsRefusedBeforeFlying) {
  SimulationSettings s = short_flight(line_mission(10, 5));
  s.physics.airframe.propulsion.max_speed_rad_s = 500;  // 4 × 2 N < 1.2 × 14.7 N
  EXPECT_THROW(simulate(s, nullptr), base::InputError);
  // Reactive without a trigger sensor; a boot as long as the flight may be.
  s = short_flight(line_mission(10, 5));
  s.scheduler.mode = SchedulerMode::reactive;
  for (auto& sensor : s.physics.sensors) sensor.trigger = false;
  EXPECT_THROW(simulate(s, nullptr), base::InputError);
  s = short_flight(line_mission(10, 5));
  s.scheduler.mode = SchedulerMode::reactive;
  s.scheduler.reactive.boot_s = s.scheduler.run.max_time_s;
  EXPECT_THROW(simulate(s, nullptr), base::InputError);
}

SimulationSettings reactive(SimulationSettings s) {
  s.scheduler.mode = SchedulerMode::reactive;
  s.scheduler.reactive.boot_s = 5;
  s.scheduler.run.metrics_from_s = 5;
  return s;
}

TEST(Simulation, ReactiveFlightsBootFitAndTriggerAndBothModesSeeTheSameWind) {
  const FlightMission m = line_mission(40, 10);
  SimulationSettings tt = short_flight(m, "arch");
  tt.seed = 11;
  Capture a, b, c;
  const SimulationSummary rt = simulate(tt, &a);
  const SimulationSummary rr = simulate(reactive(tt), &b);
  ASSERT_EQ(rr.status, FlightStatus::completed) << rr.lost_control_reason;
  EXPECT_TRUE(rr.reactive);
  // The boot (5 s at 400 Hz) gave every trigger sensor data; the models were refitted every
  // second after it; executions after the boot were caused by triggers, the failsafe or a leg.
  ASSERT_EQ(rr.triggers.size(), 5u);
  for (const auto& t : rr.triggers) {
    EXPECT_GE(t.refits, static_cast<std::int64_t>(rr.flight_time_s - 5) - 1) << t.sensor;
    EXPECT_GT(t.dataset, 0u) << t.sensor;
  }
  EXPECT_EQ(rr.executions.by_cause[0], 0);  // no time-triggered release after the boot
  EXPECT_EQ(rr.executions.by_cause[1], 0);  // metrics start at the boot's end
  EXPECT_EQ(rr.executions.total,
            rr.executions.by_cause[2] + rr.executions.by_cause[3] + rr.executions.by_cause[4]);
  EXPECT_LT(rr.cross_track_m.max, 2.0);
  // Common random numbers: the wind at the body differs only by the log profile's dependence on
  // the height flown (centimetres here); another seed's turbulence differs by its σ.
  SimulationSettings other = tt;
  other.seed = 12;
  simulate(other, &c);
  double same = 0, different = 0;
  const std::size_t n = std::min({a.kept.size(), b.kept.size(), c.kept.size()});
  for (std::size_t k = 0; k < n; ++k) {
    same = std::max(same, norm(a.kept[k].wind_m_s - b.kept[k].wind_m_s));
    different = std::max(different, norm(a.kept[k].wind_m_s - c.kept[k].wind_m_s));
  }
  EXPECT_LT(same, 0.05);
  EXPECT_GT(different, 0.3);
  EXPECT_GT(rt.executions.total, 0);
}

TEST(Simulation, TheOracleChangesNothingAndLabelsEverySampleAfterTheBoot) {
  SimulationSettings off = reactive(short_flight(line_mission(20, 8), "rugby"));
  off.seed = 5;
  SimulationSettings on = off;
  on.scheduler.reactive.oracle = true;
  Capture a, b;
  const SimulationSummary ra = simulate(off, &a), rb = simulate(on, &b);
  EXPECT_EQ(a.rows, b.rows);
  EXPECT_EQ(a.seconds, b.seconds);
  EXPECT_FALSE(ra.oracle);
  ASSERT_TRUE(rb.oracle);
  const auto& o = *rb.oracle;
  // Every trigger-sensor sample from the boot's end is labelled once; the samples that fired are
  // the triggers counted after the boot (the scheduler checks none during it).
  std::int64_t fired = 0;
  for (const auto& t : rb.triggers) fired += t.triggers;
  EXPECT_EQ(o.tp + o.fp, fired);
  EXPECT_GT(o.tn + o.fn + o.tp + o.fp, 0);
  SimulationSummary strip = rb;
  strip.oracle.reset();
  const SummaryInputs in{"l", "q", "r", "rugby", 5, 3, false};
  EXPECT_EQ(summary_json(ra, in, off), summary_json(strip, in, on));
}

// Paper 002's LAB protocol from the bundled files: quad-f450, reactive.yaml, the LAB mission
// (random:8@20x20 at 3 m/s and 5 m) looped, as `swath-control run paper` flies it.
SimulationSettings paper_lab_flight(std::uint64_t seed) {
  const std::string share = SWATH_SOURCE_DIR "/share/";
  const std::string vehicle_file = share + "vehicles/quad-f450.yaml";
  const std::string vehicle_text = base::read_text_file(vehicle_file, "vehicle file");
  SimulationSettings s;
  s.seed = seed;
  s.loop = true;
  s.physics = vehicle::parse_vehicle(vehicle_text, vehicle_file);
  s.control = parse_vehicle_control(vehicle_text, vehicle_file);
  s.battery = energy::parse_battery_section(vehicle_text, vehicle_file);
  const std::string scheduler_file = share + "schedulers/reactive.yaml";
  s.scheduler = parse_scheduler_config(base::read_text_file(scheduler_file, "scheduler file"),
                                       scheduler_file);
  const std::string lab_file = share + "environments/lab.yaml";
  s.environment =
      vehicle::parse_environment(base::read_text_file(lab_file, "environment file"), lab_file);
  MissionOptions options;
  options.altitude_m = 5;
  s.mission = closed_for_loop(read_flight_mission("random:8@20x20", options, seed, nullptr));
  s.speed_m_s = 3;
  return s;
}

TEST(Simulation, ReactiveFeedbackDoesNotRatchetIntoACrash) {
  // With a 10 µs dead band most executions leave the output unchanged. Paper 002's feedback rule
  // (false positives above x* only) raised the gyro's x* at every refit until β2 < 0 (~446 s),
  // after which baro and GPS fired on every sample, GPS held off the watchdog, and control was
  // lost at ~604 s. 700 s on three seeds must keep control, with the failsafe still running.
#ifdef SWATH_SANITIZED
  // Seed 1 only under the sanitizers: each 700 s flight takes about a minute there.
  const std::vector<std::uint64_t> seeds = {1};
#else
  const std::vector<std::uint64_t> seeds = {1, 2, 3};
#endif
  for (const std::uint64_t seed : seeds) {
    SimulationSettings s = paper_lab_flight(seed);
    s.control.controller.change_threshold_us = 10;
    s.scheduler.run.max_time_s = 700;
    // The battery is not what is tested: a bigger one, so that the reserve does not end the
    // flight first (the sparse loop draws more than the 5 Ah give in 700 s to 20 %).
    s.battery.capacity_ah = 10;
    const SimulationSummary r = simulate(s, nullptr);
    EXPECT_EQ(r.status, FlightStatus::time_limit)
        << "seed " << seed << ": " << r.lost_control_reason;
    EXPECT_LT(r.max_tilt_deg, 45) << "seed " << seed;
    // The loop ran at least at the failsafe's 10 Hz throughout (executions per second, p5).
    EXPECT_GE(r.executions.per_second_p5, 10) << "seed " << seed;
  }
}

TEST(Simulation, AFasterLoopHoldsHeadingNoWorse) {
  // Paper 002's LAB mission looped for 300 s, time-triggered at 100, 400 and 1,000 Hz, the same
  // seed (the same wind and sensor noise). A faster loop has less delay: its disturbance-only yaw
  // error may fall but must not rise (10 % allowed for the flights' different paths; measured
  // 0.53°, 0.44°, 0.41°). With the magnetometer weighted by the execution's interval, its gain
  // per second fell with the rate and the heading drifted with the gyro's bias: 0.54°, 0.92°,
  // 2.39°.
  std::vector<double> yaw_deg;
  for (const double rate_hz : {100.0, 400.0, 1000.0}) {
    SimulationSettings s = paper_lab_flight(1);
    s.scheduler.mode = SchedulerMode::time_triggered;
    s.scheduler.rate_hz = rate_hz;
    s.scheduler.run.max_time_s = 300;
    const SimulationSummary r = simulate(s, nullptr);
    ASSERT_EQ(r.status, FlightStatus::time_limit) << rate_hz << " Hz";
    ASSERT_GT(r.disturbance_share, 0.02) << rate_hz << " Hz";
    yaw_deg.push_back(r.attitude_error_disturbance_deg[2].rms);
  }
  EXPECT_LE(yaw_deg[1], 1.1 * yaw_deg[0]) << "400 Hz against 100 Hz";
  EXPECT_LE(yaw_deg[2], 1.1 * yaw_deg[1]) << "1,000 Hz against 400 Hz";
}

// Every execution as executions.csv would have it.
struct ExecutionLog : SimulationObserver {
  std::vector<ExecutionRow> rows;
  void on_execution(const ExecutionRow& r) override { rows.push_back(r); }
};

// The nodes a change of `inputs` reaches, grown to a fixed point (not in the graph's order).
std::uint32_t downstream(unsigned inputs) {
  const auto graph = control_graph();
  std::uint32_t set = 0;
  for (bool grew = true; grew;) {
    grew = false;
    for (std::size_t j = 0; j < graph.size(); ++j)
      if (((graph[j].inputs & inputs) || (graph[j].upstream & set)) && !(set >> j & 1)) {
        set |= 1u << j;
        grew = true;
      }
  }
  return set;
}

TEST(Simulation, PartialGraphExecutionChargesTheTriggeredInputsDownstreamNodesAndWholeAllOfThem) {
  // A core with nothing else to do (no drivers, trigger checks, refits or background work), so
  // each execution runs from start to end uninterrupted for exactly the cycles it is charged.
  SimulationSettings s = reactive(short_flight(line_mission(40, 10), "arch"));
  s.seed = 3;
  s.control.controller.change_threshold_us = 10;  // many sensors fire, alone and together
  ComputerSettings& cpu = s.control.computer;
  cpu.driver_cycles = cpu.trigger_check_cycles = cpu.refit_cycles_per_point = 0;
  cpu.background.clear();
  const FlightComputer core(cpu);
  const std::int64_t whole = cpu.control_cycles + cpu.dispatch_cycles;
  const auto input_of = [](const std::string& sensor) {
    if (sensor == "gyro") return GraphInput::gyro;
    if (sensor == "accel") return GraphInput::accel;
    if (sensor == "mag") return GraphInput::mag;
    if (sensor == "baro") return GraphInput::baro;
    EXPECT_EQ(sensor, "gps");
    return GraphInput::position;
  };
  for (const GraphExecution mode : {GraphExecution::partial, GraphExecution::whole}) {
    s.scheduler.reactive.graph_execution = mode;
    ExecutionLog log;
    const SimulationSummary r = simulate(s, &log);
    ASSERT_EQ(r.status, FlightStatus::completed) << r.lost_control_reason;
    int cheaper = 0;
    for (const ExecutionRow& row : log.rows) {
      std::int64_t expected = whole;
      // Only executions caused by triggers and new legs alone run part of the graph.
      if (mode == GraphExecution::partial && row.causes != 0 && (row.causes & ~20u) == 0) {
        unsigned inputs =
            (row.causes & 16u) ? 1u << static_cast<unsigned>(GraphInput::setpoint) : 0;
        std::istringstream names(row.sensors);
        for (std::string name; std::getline(names, name, '+');)
          inputs |= 1u << static_cast<unsigned>(input_of(name));
        expected = graph_cycles(downstream(inputs), cpu.control_cycles) + cpu.dispatch_cycles;
      }
      cheaper += expected < whole;
      ASSERT_EQ(row.cycles, expected) << row.start_s << " " << row.sensors;
      ASSERT_NEAR(row.end_s - row.start_s, 1e-9 * static_cast<double>(core.duration_ns(expected)),
                  2e-9)
          << row.start_s << " " << row.sensors;
    }
    // Partial execution had executions to spare (a baro or GPS fix alone, a new leg).
    if (mode == GraphExecution::partial) {
      EXPECT_GT(cheaper, 0);
    }
  }
}

TEST(Simulation, PRunActsWhereOutputsOftenStayTheSameAndNotWhereTheyNeverDo) {
  // With a 10 µs dead band TT400 leaves about half the outputs unchanged, the fitted L(x) spans
  // P_run, and a higher P_run runs fewer executions. With the 1 µs default almost every
  // execution changes the output, the fit's L(0) is above 0.99, and P_run from 0.2 to 0.8 fires
  // on every sample alike: the same flight.
  std::vector<double> dead_band, fine;
  for (const double p : {0.2, 0.5, 0.8}) {
    SimulationSettings s = paper_lab_flight(1);
    s.scheduler.run.max_time_s = 90;
    s.scheduler.reactive.p_run = p;
    fine.push_back(simulate(s, nullptr).executions.per_second_mean);
    s.control.controller.change_threshold_us = 10;
    dead_band.push_back(simulate(s, nullptr).executions.per_second_mean);
  }
  // Measured 537, 69 and 54 executions/s: steeply to P_run 0.5, less after it.
  EXPECT_GT(dead_band[0], 1.5 * dead_band[1]);
  EXPECT_GT(dead_band[1], 1.1 * dead_band[2]);
  EXPECT_EQ(fine[0], fine[2]);
  EXPECT_GT(fine[0], 900);  // every gyro sample (1 kHz)
}

TEST(Simulation, TheHeadingSlewsAtWaypointsAndTheDisturbanceMetricLeavesTurnsOut) {
  // A 20 m square: a quarter turn at each corner. Stepped, the yaw error peaks near 90°; slewed
  // at 45°/s with the rate as feed-forward it stays within a few degrees. The disturbance-only
  // figures leave out the turns and stops (and the second after each), so they are smaller still.
  FlightMission square;
  square.name = "square";
  const std::vector<Vec3> corners{{0, 0, 10}, {20, 0, 10}, {20, 20, 10}, {0, 20, 10}, {0, 0, 10}};
  for (std::size_t k = 0; k + 1 < corners.size(); ++k)
    square.legs.push_back({corners[k], corners[k + 1]});
  SimulationSettings slewed = short_flight(square);
  SimulationSettings stepped = slewed;
  stepped.control.controller.limits.yaw_slew_dps = 0;
  const SimulationSummary a = simulate(slewed, nullptr), b = simulate(stepped, nullptr);
  ASSERT_EQ(a.status, FlightStatus::completed);
  ASSERT_EQ(b.status, FlightStatus::completed);
  EXPECT_GT(b.attitude_error_deg[2].max, 60);
  EXPECT_LT(a.attitude_error_deg[2].max, 10);
  EXPECT_LT(a.attitude_error_deg[2].rms, 0.2 * b.attitude_error_deg[2].rms);
  EXPECT_GT(a.disturbance_share, 0.1);
  EXPECT_LT(a.disturbance_share, 0.9);
  for (int k = 0; k < 3; ++k)
    EXPECT_LE(a.attitude_error_disturbance_deg[k].max, a.attitude_error_deg[k].max) << k;
  // Background work is released at its rates over the flight and reported.
  EXPECT_NEAR(static_cast<double>(a.background_released), 70 * a.flight_time_s, 3);
  EXPECT_EQ(a.background_completed + a.background_skipped, a.background_released);
  EXPECT_GT(a.background_latency_mean_ms, 0);
}

TEST(Simulation, AtCruiseTheAttitudeSetpointIsSteadyAndItsPitchIsTheDragBalance) {
  // A straight 200 m leg at 5 m/s in calm air with noiseless, unquantised sensors (the baro's
  // steps alone swing the thrust's tilt by ~0.25°). The carrot is updated at 50 Hz; held between
  // updates it fell behind by up to 0.1 m and jumped back, a 1° sawtooth in the attitude setpoint
  // whose 50 Hz rows sat on its peak (a mean pitch error of 0.5° there, ~0 over every execution).
  // Advanced to each execution's time, the setpoint is steady, the pitch error averages to 0,
  // and the pitch is the drag balance: level flight at v along body x tilted θ nose down needs
  // sin θ = (D_x v cos θ + ½ ρ CdA_x v² cos² θ) / (m g) (thrust along body z, drag per body axis).
  SimulationSettings s = short_flight(line_mission(200, 10));
  s.speed_m_s = 5;
  s.scheduler.run.output_interval_s = 0.001;
  for (vehicle::SensorSettings& sensor : s.physics.sensors) {
    sensor.noise = sensor.bias_constant = sensor.bias_random_walk_per_sqrt_s = 0;
    sensor.velocity_noise_m_s = sensor.markov_sigma_m = sensor.lsb = 0;
  }
  s.physics.airframe.frame.torque_noise_sigma_nm = 0;
  Capture c;
  const SimulationSummary r = simulate(s, &c);
  ASSERT_EQ(r.status, FlightStatus::completed);
  // The carrot cruises from 5 s to 40 s; the drone has settled onto it by 15 s.
  double error_sum = 0, logged_error_sum = 0, setpoint_sum = 0, truth_sum = 0, worst_swing = 0;
  int n = 0, logged = 0;
  double window_lo = INFINITY, window_hi = -INFINITY, window_start = 15;
  for (const TimeseriesRow& row : c.kept) {
    if (row.t_s < 15 || row.t_s > 38) continue;
    error_sum += row.setpoint_deg.y - row.attitude_deg.y;
    if (std::lround(row.t_s * 1000) % 20 == 0) {  // the rows timeseries.csv writes by default
      logged_error_sum += row.setpoint_deg.y - row.attitude_deg.y;
      ++logged;
    }
    setpoint_sum += row.setpoint_deg.y;
    truth_sum += row.attitude_deg.y;
    ++n;
    if (row.t_s >= window_start + 0.3) {  // 300 ms windows of consecutive executions
      worst_swing = std::max(worst_swing, window_hi - window_lo);
      window_lo = INFINITY, window_hi = -INFINITY, window_start = row.t_s;
    }
    window_lo = std::min(window_lo, row.setpoint_deg.y);
    window_hi = std::max(window_hi, row.setpoint_deg.y);
  }
  ASSERT_GT(n, 20'000);
  EXPECT_LT(worst_swing, 0.1) << "pitch setpoint peak to peak, degrees";
  EXPECT_LT(std::abs(error_sum / n), 0.02) << "mean pitch error, degrees";
  EXPECT_LT(std::abs(logged_error_sum / logged), 0.02) << "mean pitch error at 50 Hz, degrees";
  // The drag balance by fixed-point iteration (a contraction: θ is a few degrees).
  const vehicle::Frame& f = s.physics.airframe.frame;
  const double v = s.speed_m_s, rho = s.environment.air_density_kg_m3;
  double theta = 0;
  for (int k = 0; k < 100; ++k) {
    const double along = v * std::cos(theta);
    theta = std::asin(
        (f.drag_linear_n_per_m_s.x * along + 0.5 * rho * f.drag_cda_m2.x * along * along) /
        (f.mass_kg * s.environment.gravity_m_s2));
  }
  const double pitch_deg = -theta * 180 / std::numbers::pi;  // nose down flying east
  EXPECT_NEAR(truth_sum / n, pitch_deg, 0.05);
  EXPECT_NEAR(setpoint_sum / n, pitch_deg, 0.05);
}

TEST(Experiment, TheIntervalIsStudentsTAndImprovementsArePaired) {
  // n = 5: t(0.975, 4) = 2.7764451051977987 (tables); mean 3, sample sd √2.5.
  const MeanInterval m = mean_interval({1, 2, 3, 4, 5});
  EXPECT_DOUBLE_EQ(m.mean, 3);
  EXPECT_NEAR(m.high - m.mean, 2.7764451051977987 * std::sqrt(2.5 / 5), 1e-12);
  EXPECT_NEAR(m.mean - m.low, m.high - m.mean, 1e-12);
  EXPECT_EQ(mean_interval({7}).low, 7);
  // Pairs: the baseline's error halves in the mode → +50 %; flight time 10 % longer → +10 %.
  std::vector<FlightFigures> base(3), mode(3);
  for (int k = 0; k < 3; ++k) {
    base[k].attitude_rms_deg = 2.0 + k;
    mode[k].attitude_rms_deg = (2.0 + k) / 2;
    base[k].flight_time_s = 100.0 * (k + 1);
    mode[k].flight_time_s = 110.0 * (k + 1);
  }
  const Improvements i = paired_improvements(base, mode);
  EXPECT_NEAR(i.attitude.mean, 0.5, 1e-12);
  EXPECT_NEAR(i.attitude.high - i.attitude.low, 0, 1e-12);
  EXPECT_NEAR(i.flight_time.mean, 0.1, 1e-12);
  EXPECT_EQ(i.cross_track.n, 0);  // baselines of 0 are skipped
}

TEST(Mission, RandomSpecsAreReadAndTheirPointsLieInTheBox) {
  const auto spec = parse_random_spec("random:8@170x120");
  ASSERT_TRUE(spec);
  EXPECT_EQ(spec->waypoints, 8);
  const FlightMission m = random_mission(*spec, 5, 42);
  ASSERT_EQ(m.legs.size(), 7u);
  for (const auto& leg : m.legs)
    for (const Vec3& p : leg) {
      EXPECT_GE(p.x, 0);
      EXPECT_LE(p.x, 170);
      EXPECT_GE(p.y, 0);
      EXPECT_LE(p.y, 120);
      EXPECT_EQ(p.z, 5);
    }
  EXPECT_FALSE(parse_random_spec("meadow.geojson"));
  for (const char* bad : {"random:", "random:1@20x20", "random:8@20", "random:8@-1x5",
                          "random:8.5@20x20", "random:8@1e9x1", "random:x@ax"})
    EXPECT_THROW(parse_random_spec(bad), base::InputError) << bad;
}

TEST(Mission, AStagePlanIsFlownAlongItsGuidedPathThroughEveryTriggeringPoint) {
  MissionOptions o;
  o.start_m = {25, 146};  // plans/survey-sim.yaml's start
  o.stage_speed_m_s = 5;
  const std::string file = SWATH_SOURCE_DIR "/plans/survey.stages";
  const FlightMission m = read_flight_mission(file, o, 1, nullptr);
  ASSERT_EQ(m.legs.size(), 1u);
  const auto& path = m.legs.front();
  ASSERT_GT(path.size(), 100u);
  EXPECT_NEAR(path.front().x, 25, 1e-6);
  EXPECT_NEAR(path.front().y, 146, 1e-6);
  // The guidance switches stage within 5 m (trigger_radius_m) of each triggering point, taken
  // from the plan's own stage fields at the highest parameters; the points are about 0.5 m apart.
  const energy::Plan plan = energy::read_plan(file);
  std::vector<double> c;
  for (const energy::Interval& b : plan.stages.front().trajectory) c.push_back(b.hi);
  std::size_t from = 0;
  for (const energy::StageField& f : energy::stage_fields(plan, c)) {
    double best = INFINITY;
    std::size_t at = from;
    for (std::size_t k = from; k < path.size(); ++k) {
      const double d = std::hypot(path[k].x - f.trigger.x, path[k].y - f.trigger.y);
      if (d < best) best = d, at = k;
    }
    EXPECT_LT(best, 5.0 + 0.6) << "stage " << f.stage;
    from = at;  // in order
  }
  for (const Vec3& p : path) EXPECT_EQ(p.z, 5);
}

TEST(Config, OverridesReachTheReadersAndMisspeltKeysAreRefused) {
  const std::string text = "mode: time_triggered\nrate_hz: 400\n";
  const SchedulerConfig c = parse_scheduler_config(
      apply_overrides(text, "tt.yaml", {{"rate_hz", "200"}, {"run.max_time_s", "60"}}), "tt.yaml");
  EXPECT_EQ(c.rate_hz, 200);
  EXPECT_EQ(c.run.max_time_s, 60);
  EXPECT_THROW(
      parse_scheduler_config(apply_overrides(text, "tt.yaml", {{"run.max_tme_s", "60"}}), "x"),
      base::InputError);
  EXPECT_THROW(apply_overrides(text, "tt.yaml", {{"rate_hz.x", "1"}}), base::InputError);
  EXPECT_THROW(apply_overrides(text, "tt.yaml", {{"rate_hz", "[1, "}}), base::InputError);
}

}  // namespace
}  // namespace swath::control
