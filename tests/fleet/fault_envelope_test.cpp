// The safety envelope under faults (docs/swath-fleet.md, "Safety envelope"): random worlds and
// fleets (2-8 drones, homes shared, in a row or scattered), link losses and battery drops at
// random times and at times inside climbs and descents, judged by a checker of this file's own
// that reads only the written events: separation between samples (positions interpolated every
// 0.05 s), the ceiling, and every charge logged at or above 0. The runtime's `check` is not used.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "swath/fleet/apps.hpp"
#include "swath/fleet/faults.hpp"
#include "swath/fleet/fleet_file.hpp"
#include "swath/fleet/runtime.hpp"
#include "swath/vehicle/random.hpp"
#include "swath/worlds/worlds.hpp"

// Its own namespace: the fleet tests build as one unit beside envelope_test.cpp's helpers.
namespace swath::fleet::fault_envelope {
namespace {

using json = nlohmann::json;

// ---- The checker: events.jsonl alone. ----

struct Fix {  // a logged position of one drone
  double t_s, x_m, y_m, z_m;
  bool lost;
};

std::vector<json> events_of(const std::string& text) {
  std::vector<json> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(json::parse(line));
  return out;
}

// Each drone's positions in time order: drone_state at t_s, drone_mode at its own at_s.
std::map<int, std::vector<Fix>> fixes_of(const std::vector<json>& events) {
  std::map<int, std::vector<Fix>> out;
  for (const json& e : events) {
    const std::string ev = e.value("ev", "");
    if (ev != "drone_state" && ev != "drone_mode") continue;
    const double t_s = ev == "drone_mode" ? e["at_s"].get<double>() : e["t_s"].get<double>();
    out[e["drone"].get<int>()].push_back(
        {t_s, e["x_m"], e["y_m"], e["alt_m"], e["state"].get<std::string>() == "lost"});
  }
  for (auto& [drone, fixes] : out)
    std::stable_sort(fixes.begin(), fixes.end(),
                     [](const Fix& a, const Fix& b) { return a.t_s < b.t_s; });
  return out;
}

// Where a drone is at t, straight between its fixes; false when it is not airborne then (on the
// ground, lost, or outside its log).
bool airborne_at(const std::vector<Fix>& fixes, double t_s, std::array<double, 3>& at) {
  auto hi = std::upper_bound(fixes.begin(), fixes.end(), t_s,
                             [](double t, const Fix& f) { return t < f.t_s; });
  if (hi == fixes.begin()) return false;
  const Fix& a = *(hi - 1);
  const Fix& b = hi == fixes.end() ? a : *hi;
  if (a.lost || b.lost) return false;
  const double u = b.t_s > a.t_s ? (t_s - a.t_s) / (b.t_s - a.t_s) : 0.0;
  at = {a.x_m + u * (b.x_m - a.x_m), a.y_m + u * (b.y_m - a.y_m), a.z_m + u * (b.z_m - a.z_m)};
  return at[2] > 1e-9;
}

// The envelope's breaches in `events_jsonl`, one line each (the first few of each kind).
std::vector<std::string> breaches(const std::string& events_jsonl) {
  const std::vector<json> events = events_of(events_jsonl);
  const json& env = events.front()["envelope"];
  const double sep_m = env["separation_m"], ceiling_m = env["ceiling_m"];
  std::vector<std::string> out;
  int soc_low = 0, above = 0, near = 0;
  double end_s = 0;
  for (const json& e : events) {
    end_s = std::max(end_s, e["t_s"].get<double>());
    if (e.contains("soc") && e["soc"].get<double>() < 0 && soc_low++ < 3)
      out.push_back(e.dump() + ": charge below 0");
    if (e.contains("alt_m") && e["alt_m"].get<double>() > ceiling_m + 1e-6 && above++ < 3)
      out.push_back(e.dump() + ": above the ceiling");
  }
  const auto fixes = fixes_of(events);
  for (double t_s = 0; t_s <= end_s + 1e-9; t_s += 0.05) {
    std::vector<std::pair<int, std::array<double, 3>>> up;
    for (const auto& [drone, f] : fixes)
      if (std::array<double, 3> p; airborne_at(f, t_s, p)) up.push_back({drone, p});
    for (std::size_t i = 0; i < up.size(); ++i)
      for (std::size_t j = 0; j < i; ++j) {
        const auto& a = up[i].second;
        const auto& b = up[j].second;
        const double d_m = std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
        if (d_m < sep_m - 1e-6 && near++ < 3)
          out.push_back("t " + std::to_string(t_s) + " s: drones " + std::to_string(up[j].first) +
                        " and " + std::to_string(up[i].first) + " " + std::to_string(d_m) +
                        " m apart");
      }
  }
  return out;
}

// ---- Random worlds, fleets and fault schedules. ----

double uniform(vehicle::SplitMix64& r, double lo, double hi) {
  return lo + (hi - lo) * r.uniform();
}

// Tasks round the homes (within 40 m): fly_to and hover, some with a second leg, some same_drone.
std::string world_text(vehicle::SplitMix64& r) {
  std::string w = "kind: static\ntasks:\n";
  const int tasks = 3 + static_cast<int>(r.next() % 8);
  const auto place = [&] {
    return "{fly_to: {x_m: " + std::to_string(uniform(r, -40, 40)) +
           ", y_m: " + std::to_string(uniform(r, -40, 40)) + "}}";
  };
  for (int k = 0; k < tasks; ++k) {
    w += "  - {name: t" + std::to_string(k) + (r.uniform() < 0.3 ? ", same_drone: true" : "") +
         ", actions: [" + place() + ", {hover: " + std::to_string(uniform(r, 1, 30)) + "}";
    if (r.uniform() < 0.4) w += ", " + place() + ", {hover: 2}";
    w += "]}\n";
  }
  return w;
}

// 2-8 drones at one home, in a row 6 m apart, or scattered within 12 m (some nearer than the
// separation); charges and flight times short enough that they come home often.
std::vector<DroneSpec> fleet(vehicle::SplitMix64& r) {
  const int n = 2 + static_cast<int>(r.next() % 7);
  const int homes = static_cast<int>(r.next() % 3);
  std::vector<DroneSpec> out(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    DroneSpec& d = out[static_cast<std::size_t>(i)];
    d.drone.name = "d" + std::to_string(i);
    if (homes == 1) d.home_m = {6.0 * i, 0, 0};
    if (homes == 2) d.home_m = {uniform(r, -6, 6), uniform(r, -6, 6), 0};
    d.battery.initial_soc = uniform(r, 0.4, 1.0);
    d.max_flight_time_s = uniform(r, 40, 200);
    d.recharge_s = uniform(r, 5, 30);
  }
  return out;
}

// When each drone climbs from the ground or descends to it in `events_jsonl`: [t0, t1] windows
// (a take-off's climb to its layer, a landing's descent, both at 3 m/s).
std::vector<std::pair<int, std::array<double, 2>>> vertical_windows(const std::string& text) {
  std::vector<std::pair<int, std::array<double, 2>>> out;
  std::map<int, json> last;
  for (const json& e : events_of(text)) {
    if (e.value("ev", "") != "drone_mode") continue;
    const int drone = e["drone"];
    const double t_s = e["at_s"], z_m = e["alt_m"];
    const std::string state = e["state"];
    if (state == "flying" && z_m == 0) out.push_back({drone, {t_s, t_s + (20 + 5 * drone) / 3.0}});
    if (state == "charging" && last.count(drone)) {
      const double top_m = last[drone]["alt_m"];
      out.push_back({drone, {t_s - top_m / 3.0, t_s}});
    }
    last[drone] = e;
  }
  return out;
}

// Faults at random times (160 per drone-hour of link losses and battery drops) and up to six
// more inside the climbs and descents of the run without faults.
std::vector<FaultEvent> faults(vehicle::SplitMix64& r, const std::vector<DroneSpec>& drones,
                               const std::string& calm_events, std::uint64_t seed) {
  std::vector<std::string> names;
  for (const DroneSpec& d : drones) names.push_back(d.drone.name);
  std::vector<FaultEvent> out =
      random_faults(seed, 160, {FaultKind::link_loss, FaultKind::battery_drop}, names, 300, 10);
  const auto windows = vertical_windows(calm_events);
  for (int k = 0; k < 6 && !windows.empty(); ++k) {
    const auto& [drone, w] = windows[r.next() % windows.size()];
    FaultEvent f;
    f.drone = drone;
    f.t_s = std::round(uniform(r, w[0], w[1]) * 10) / 10;  // on the tick grid
    f.kind = r.uniform() < 0.5 ? FaultKind::link_loss : FaultKind::battery_drop;
    f.duration_s = uniform(r, 3, 20);
    f.soc = uniform(r, 0.02, 0.5);
    out.push_back(f);
  }
  std::stable_sort(out.begin(), out.end(), [](const FaultEvent& a, const FaultEvent& b) {
    return a.t_s != b.t_s ? a.t_s < b.t_s : a.drone < b.drone;
  });
  return out;
}

App static_app() {
  for (App& a : builtin_apps())
    if (a.name == "static") return a;
  ADD_FAILURE() << "no static app";
  return {};
}

// Drones `a` at (0, 0) and `b` at `b_home`, the defaults otherwise.
std::vector<DroneSpec> two_drones(const std::string& a, const std::string& b, Vec3 b_home) {
  std::vector<DroneSpec> drones(2);
  drones[0].drone.name = a;
  drones[1].drone.name = b;
  drones[1].home_m = b_home;
  return drones;
}

// A battery drop of `drone` to `soc` at `t_s`.
FaultEvent battery_drop(double t_s, int drone, double soc) {
  FaultEvent f;
  f.t_s = t_s;
  f.drone = drone;
  f.kind = FaultKind::battery_drop;
  f.soc = soc;
  return f;
}

RuntimeSettings settings(std::uint64_t seed, std::vector<FaultEvent> f) {
  RuntimeSettings s;
  s.app_name = "static";
  s.seed = seed;
  s.max_time_s = 300;
  s.faults = std::move(f);
  return s;
}

// 120 random worlds and fault schedules: no breach of the envelope in any, and charge never
// below 0 in the record either.
TEST(FaultEnvelope, RandomFaultsKeepSeparationCeilingAndCharge) {
  const App app = static_app();
  int runs_with_breach = 0, faults_in_all = 0, exhausted = 0;
  for (std::uint64_t seed = 1; seed <= 120; ++seed) {
    vehicle::SplitMix64 r = vehicle::SplitMix64::stream(seed, "fault-envelope");
    const auto world = worlds::parse_world(world_text(r), "w.yaml");
    const std::vector<DroneSpec> drones = fleet(r);
    const RunRecord calm = run_app(app, *world, drones, settings(seed, {}));
    const RunRecord run =
        run_app(app, *world, drones, settings(seed, faults(r, drones, calm.events_jsonl, seed)));
    faults_in_all += run.faults_happened;
    exhausted += run.battery_exhausted;
    std::vector<std::string> found = breaches(run.events_jsonl);
    for (const DroneRecord& d : run.drones)
      if (d.final_soc < 0)
        found.push_back(d.name + " ends at charge " + std::to_string(d.final_soc));
    if (!found.empty()) ++runs_with_breach;
    for (const std::string& b : found) ADD_FAILURE() << "seed " << seed << ": " << b;
    EXPECT_TRUE(breaches(calm.events_jsonl).empty()) << "seed " << seed << " without faults";
  }
  EXPECT_EQ(runs_with_breach, 0);
  EXPECT_GT(faults_in_all, 1000);  // the schedules did fault
  RecordProperty("faults", faults_in_all);
  RecordProperty("battery_exhausted", exhausted);
}

// ---- The tester's smallest cases (/work/t-fleet/min), in process. ----

std::vector<DroneSpec> two_on_one_home(double d0_max_flight_s) {
  return parse_fleet_file(
      "drones:\n"
      "  - {name: d0, endurance_s: 900, speed_m_s: 10, home_m: {x_m: 0, y_m: 0},"
      " max_flight_time_s: " +
          std::to_string(d0_max_flight_s) +
          "}\n"
          "  - {name: d1, endurance_s: 900, speed_m_s: 10, home_m: {x_m: 0, y_m: 0}}\n",
      "fleet.yaml", {42.3601, -71.0942});
}

// Each drone's landings (the times it begins charging) in `events_jsonl`.
std::map<int, std::vector<double>> landings(const std::string& events_jsonl) {
  std::map<int, std::vector<double>> out;
  for (const json& e : events_of(events_jsonl))
    if (e.value("ev", "") == "drone_mode" && e["state"] == "charging")
      out[e["drone"].get<int>()].push_back(e["at_s"].get<double>());
  return out;
}

// d1's battery drops while d0 hovers over their shared home: both hold over it, d0 at 20 m and
// d1 at 25 m. d0, lowest, must land (d1 straight above it is not in its way down), then d1; both
// within d0's 45 s flight time and d1's charge, nobody run dry.
TEST(FaultEnvelope, LowestOverASharedHomeLandsFirst) {
  const auto world = worlds::parse_world(
      "kind: static\ntasks:\n"
      "  - {name: t0, actions: [{fly_to: {x_m: -2.6, y_m: -7.1}}, {hover: 5}]}\n"
      "  - {name: t1, actions: [{fly_to: {x_m: -0.4, y_m: 7.4}}, {hover: 40}]}\n",
      "w.yaml");
  const FaultEvent drop = battery_drop(29, 1, 0.15);
  RuntimeSettings s = settings(1, {drop});
  s.max_time_s = 600;
  const RunRecord run = run_app(static_app(), *world, two_on_one_home(45), s);
  EXPECT_TRUE(breaches(run.events_jsonl).empty());
  EXPECT_EQ(run.battery_exhausted, 0);
  const auto landed = landings(run.events_jsonl);
  ASSERT_TRUE(landed.count(0) && landed.count(1));
  EXPECT_LE(landed.at(0).front(), 45.0);  // d0's max_flight_time_s, from its take-off at 0
  EXPECT_LT(landed.at(0).front(), landed.at(1).front());
  EXPECT_LT(landed.at(1).front(), 60.0);
}

// A drone is not sent to work in the column of an airborne drone of a higher layer (scheduler.hpp,
// LandingColumn): b (25 m) comes home early on a battery drop while a (20 m) is free and a
// 900 s hover waits at b's home. Sent there while b was out, a hovered under b's column and b
// held over it until its battery ran out and it came down through a (the tester's case); now the
// hover waits until b is down, b lands at once, and no battery runs dry.
TEST(FaultEnvelope, NoDroneIsSentToWorkUnderTheColumnOfOneStillToLand) {
  const auto world = worlds::parse_world(
      "kind: static\ntasks:\n"
      "  - {name: far1, actions: [{fly_to: {x_m: -80, y_m: 0}}, {hover: 200}]}\n"
      "  - {name: far2, actions: [{fly_to: {x_m: 60, y_m: 0}}, {hover: 1}]}\n"
      "  - {name: block, after: [far2], actions: [{fly_to: {x_m: -6, y_m: 0}}, {hover: 900}]}\n",
      "w.yaml");
  const std::vector<DroneSpec> drones = two_drones("a", "b", {-6, 0, 0});
  const FaultEvent drop = battery_drop(60, 1, 0.1);
  RuntimeSettings s = settings(1, {drop});
  s.max_time_s = 1500;
  const RunRecord run = run_app(static_app(), *world, drones, s);
  ASSERT_TRUE(run.completed) << run.failure;
  EXPECT_TRUE(breaches(run.events_jsonl).empty());
  EXPECT_EQ(run.battery_exhausted, 0);
  // Whenever a drone is sent to b's home, b is on the ground or is that drone.
  const std::vector<json> events = events_of(run.events_jsonl);
  std::string b_mode = "landed";
  for (const json& e : events) {
    if (e["ev"] == "drone_mode" && e["drone"] == 1) b_mode = e["state"].get<std::string>();
    if (e["ev"] == "dispatch" && e["drone"] != 1 && std::abs(e["x_m"].get<double>() + 6) < 1e-9)
      EXPECT_TRUE(b_mode == "landed" || b_mode == "charging") << e.dump() << " b " << b_mode;
  }
}

// drone 1 (of two in a row 6 m apart) loses its link 7 s into its climb, at 21 m of 25: it
// finishes the climb before it heads home, and drone 0 at 20 m passes it at least 5 m away.
TEST(FaultEnvelope, LinkLossMidClimbFinishesTheClimb) {
  const auto world = worlds::parse_world(
      "kind: static\ntasks:\n"
      "  - {name: t0, actions: [{fly_to: {x_m: 5.2, y_m: -1.8}}, {hover: 5}]}\n"
      "  - {name: t1, actions: [{fly_to: {x_m: 12.8, y_m: -1.6}}, {hover: 5}]}\n"
      "  - {name: t2, actions: [{fly_to: {x_m: 11.9, y_m: 16.7}}, {hover: 20}]}\n",
      "w.yaml");
  std::vector<DroneSpec> drones(2);
  for (int i = 0; i < 2; ++i) {
    drones[static_cast<std::size_t>(i)].drone.name = "drone-" + std::to_string(i + 1);
    drones[static_cast<std::size_t>(i)].home_m = {6.0 * i, 0, 0};
  }
  FaultEvent loss;
  loss.t_s = 7;
  loss.drone = 1;
  loss.duration_s = 10;
  const RunRecord run = run_app(static_app(), *world, drones, settings(1, {loss}));
  EXPECT_TRUE(breaches(run.events_jsonl).empty());
  // After the fault's own line (at 21 m) and until it is down, drone 1 is logged at its layer.
  for (const json& e : events_of(run.events_jsonl)) {
    if (e.value("ev", "") != "drone_mode" || e["drone"] != 1 || e["at_s"].get<double>() <= 7.0)
      continue;
    if (e["state"] == "charging") break;
    EXPECT_EQ(e["alt_m"].get<double>(), 25.0) << e.dump();
  }
}

// A battery drop to 1 % 30 m out: the drone cannot reach home and comes down where it is before
// its charge goes below 0, logged (battery_exhausted, then lost at 0 m) and counted.
TEST(FaultEnvelope, ChargeRunningOutBringsTheDroneDownWhereItIs) {
  const auto world = worlds::parse_world(
      "kind: static\ntasks:\n  - {name: t0, actions: [{fly_to: {x_m: 30, y_m: 0}}, {hover: "
      "60}]}\n",
      "w.yaml");
  const std::vector<DroneSpec> drones = two_drones("d0", "d1", {0, 6, 0});
  const FaultEvent drop = battery_drop(20, 0, 0.001);
  const RunRecord run = run_app(static_app(), *world, drones, settings(1, {drop}));
  EXPECT_TRUE(breaches(run.events_jsonl).empty());
  EXPECT_EQ(run.battery_exhausted, 1);
  EXPECT_GE(run.drones[0].final_soc, 0.0);
  bool logged = false, down = false;
  for (const json& e : events_of(run.events_jsonl)) {
    if (e.value("ev", "") == "battery_exhausted" && e["drone"] == 0) logged = true;
    if (logged && e.value("ev", "") == "drone_mode" && e["drone"] == 0 && e["state"] == "lost")
      down = down || e["alt_m"].get<double>() == 0.0;
  }
  EXPECT_TRUE(logged);
  EXPECT_TRUE(down);
  EXPECT_TRUE(run.completed);  // d1 takes over the hover
}

}  // namespace
}  // namespace swath::fleet::fault_envelope
