// No task is lost (docs/swath-fleet.md): 1,000 random fault schedules over the five
// case-study apps and `static`, each run's events.jsonl judged by the checker that reads nothing
// else; the checker itself must catch every single-rule break of a real log; the faults file
// reader.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iostream>
#include <set>
#include <sstream>

#include "swath/base/input_error.hpp"
#include "swath/fleet/apps.hpp"
#include "swath/fleet/event_check.hpp"
#include "swath/fleet/faults.hpp"
#include "swath/fleet/runtime.hpp"
#include "swath/worlds/worlds.hpp"

namespace swath::fleet {
namespace {

// Small versions of the bundled worlds: the same code paths in a fraction of the time.
const char* small_world(const std::string& app) {
  if (app == "hotspot") return "kind: hotspot\nseed: 2\nsteps: 3\n";
  if (app == "road") return "kind: road\nseed: 2\nsteps: 6\n";
  if (app == "wifi") return "kind: rf_field\nseed: 2\nfence: {width_m: 20, height_m: 20}\n";
  if (app == "tracking") return "kind: tracking\nseed: 2\nduration_s: 90\n";
  if (app == "static")
    return "kind: static\ntasks:\n"
           "  - {name: a, same_drone: true, actions: [{fly_to: {x_m: 30, y_m: 0}}, {sense: cam},"
           " {fly_to: {x_m: 0, y_m: 40}}, {hover: 3}]}\n"
           "  - {name: b, after: [a], interruptible: false, actions: [{fly_to: {x_m: -20, y_m: 5}},"
           " {custom: {name: x, s: 2}}, {fly_to: {x_m: -30, y_m: 5}}, {sense: cam}]}\n"
           "  - {name: c, actions: [{fly_to: {x_m: 10, y_m: -30}}, {sense: cam}]}\n";
  return "kind: sites\nseed: 2\narea_m: 120\n";
}

std::vector<DroneSpec> three_drones(std::uint64_t seed) {
  auto rng = vehicle::SplitMix64::stream(seed, "fleet");
  std::vector<DroneSpec> out(3);
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i].drone.name = std::array<const char*, 3>{"d0", "d1", "d2"}[i];
    out[i].home_m = {rng.uniform(-20, 20), rng.uniform(-20, 20), 0};
    if (rng.uniform() < 0.5) out[i].max_flight_time_s = rng.uniform(60, 200);
    out[i].recharge_s = rng.uniform(5, 30);
    out[i].battery.initial_soc = rng.uniform(0.5, 1.0);
    out[i].battery.reserve_soc = 0.2;
  }
  return out;
}

TEST(NoLostTask, AThousandRandomFaultSchedulesOverTheFiveApps) {
  const std::vector<FaultKind> kinds{FaultKind::link_loss, FaultKind::battery_drop,
                                     FaultKind::motor_failure, FaultKind::sensor_failure};
  std::vector<App> apps = fleet::builtin_apps();
  ASSERT_EQ(apps.size(), 6u);  // the five case studies and `static`
  int violations = 0, runs = 0, faults = 0, duplicates = 0, failed_tasks = 0, completed = 0;
  // 1,000 schedules; 200 under the sanitizers (they check memory, not counts; ~10x slower).
#ifdef SWATH_SANITIZED
  const std::uint64_t schedules = 200;
#else
  const std::uint64_t schedules = 1000;
#endif
  for (std::uint64_t k = 0; k < schedules; ++k) {
    const App& app = apps[k % apps.size()];
    const auto world = worlds::parse_world(small_world(app.name), "w.yaml");
    const std::vector<DroneSpec> drones = three_drones(k);
    std::vector<std::string> names;
    for (const auto& d : drones) names.push_back(d.drone.name);
    RuntimeSettings s;
    s.app_name = app.name;
    s.seed = k;
    s.scheduler = k % 3 == 0 ? "greedy" : "sa";
    s.max_time_s = 900;
    s.no_feasible_s = 60;
    s.faults = random_faults(k, 40 + static_cast<double>(k % 7) * 20, kinds, names, 600,
                             3 + static_cast<double>(k % 5) * 4);
    const RunRecord r = run_app(app, *world, drones, s);
    const EventCheck c = check_events(r.events_jsonl);
    ++runs;
    faults += c.faults;
    duplicates += c.duplicates;
    completed += r.completed;
    failed_tasks += c.terminal.count("task_failed") ? c.terminal.at("task_failed") : 0;
    for (const auto& v : c.violations) {
      if (violations++ < 5)
        ADD_FAILURE() << app.name << " schedule " << k << ": line " << v.line << ": " << v.rule
                      << ": " << v.message;
    }
  }
  EXPECT_EQ(violations, 0);
  // The schedules did exercise the rules: faults, late duplicates and failures happened.
  EXPECT_GT(faults, static_cast<int>(2 * schedules));
  if (schedules >= 1000) {
    EXPECT_GT(duplicates, 0);
  }  // rare: 7 in the 1,000 schedules
  EXPECT_GT(failed_tasks, 0);
  EXPECT_GT(completed, static_cast<int>(schedules / 2));
  std::cout << runs << " runs, " << faults << " faults, " << duplicates << " duplicates dropped, "
            << failed_tasks << " tasks failed visibly, " << completed << " apps completed\n";
}

// A real log, then one line changed at a time: each change breaks exactly the rule it targets.
TEST(EventCheck, CatchesEveryRuleBrokenInARealLog) {
  const App app = fleet::builtin_apps().at(1);  // multiplexing
  ASSERT_EQ(app.name, "multiplexing");
  const auto world = worlds::parse_world("kind: sites\nseed: 4\n", "w.yaml");
  std::vector<DroneSpec> drones(2);
  drones[0].drone.name = "a";
  drones[1].drone.name = "b";
  RuntimeSettings s;
  s.faults = {{30, 1, FaultKind::motor_failure, 0, 0}};
  const RunRecord r = run_app(app, *world, drones, s);
  ASSERT_TRUE(check_events(r.events_jsonl).ok());
  std::vector<std::string> lines;
  std::istringstream in(r.events_jsonl);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  auto join = [](const std::vector<std::string>& v) {
    std::string out;
    for (const auto& l : v) out += l + "\n";
    return out;
  };
  auto find = [&](const std::string& needle, std::size_t from = 0) {
    for (std::size_t i = from; i < lines.size(); ++i)
      if (lines[i].find(needle) != std::string::npos) return i;
    ADD_FAILURE() << "no " << needle;
    return std::size_t{0};
  };
  auto broken = [&](std::vector<std::string> v) {
    std::set<std::string> rules;
    for (const auto& x : check_events(join(v)).violations) rules.insert(x.rule);
    return rules;
  };
  {  // R3: a terminal event dropped
    auto v = lines;
    v.erase(v.begin() + static_cast<long>(find("\"task_done\"")));
    EXPECT_TRUE(broken(v).count("R3"));
  }
  {  // R5: a result delivered twice
    auto v = lines;
    const std::size_t i = find("\"action_done\"");
    v.insert(v.begin() + static_cast<long>(i) + 1, v[i]);
    EXPECT_TRUE(broken(v).count("R5"));
  }
  {  // R1: time going back
    auto v = lines;
    const std::size_t i = find("\"t_s\":1");
    v.insert(v.begin() + static_cast<long>(i) + 1, "{\"t_s\":0.5,\"ev\":\"note\"}");
    EXPECT_TRUE(broken(v).count("R1"));
  }
  {  // R6: a negative charge
    auto v = lines;
    const std::size_t i = find("\"drone_state\"");
    const auto at = v[i].find("\"soc\":");
    v[i] = v[i].substr(0, at) + "\"soc\":-0.1,\"state\":\"flying\"}";
    EXPECT_TRUE(broken(v).count("R6"));
  }
  {  // R8: a dispatch to the drone after its motor failed
    auto v = lines;
    const std::size_t i = find("\"motor_failure\"");
    v.insert(v.begin() + static_cast<long>(i) + 1,
             "{\"t_s\":30.0,\"ev\":\"dispatch\",\"drone\":1,\"task\":1,\"segment\":0}");
    EXPECT_TRUE(broken(v).count("R8"));
  }
  {  // R4: a task named after it ended
    auto v = lines;
    const std::size_t i = find("\"task_done\"");
    const std::string task = v[i].substr(v[i].find("\"task\":"));
    v.insert(v.begin() + static_cast<long>(i) + 1,
             "{\"t_s\":999.0,\"ev\":\"requeued\",\"drone\":0," + task);
    auto rules = broken(v);
    EXPECT_TRUE(rules.count("R4"));
  }
  {  // R7: past max_time_s
    auto v = lines;
    v.back() = "{\"t_s\":99999.0,\"ev\":\"run_end\",\"completed\":true}";
    EXPECT_TRUE(broken(v).count("R7"));
  }
  {  // R9: a dispatch of a segment never shown
    auto v = lines;
    v.insert(v.end() - 1,
             "{\"t_s\":1.0,\"ev\":\"dispatch\",\"drone\":0,\"task\":1,\"segment\":77}");
    EXPECT_TRUE(broken(v).count("R9"));
  }
  {  // R1 and R2: garbage and an unknown task
    auto v = lines;
    v.insert(v.begin() + 3, "not json");
    v.insert(v.begin() + 4,
             "{\"t_s\":0,\"ev\":\"action_done\",\"drone\":0,\"task\":4242,\"action\":0}");
    auto rules = broken(v);
    EXPECT_TRUE(rules.count("R1"));
    EXPECT_TRUE(rules.count("R2"));
  }
  EXPECT_FALSE(check_events("").ok());
}

TEST(Faults, FileFormsAndRefusals) {
  const std::vector<std::string> names{"alpha", "bravo"};
  const auto list = parse_faults(
      "- {t_s: 40, drone: bravo, kind: link_loss, duration_s: 5}\n"
      "- {t_s: 10, drone: alpha, kind: battery_drop, soc: 0.25}\n",
      "f.yaml", names, 3600);
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[0].t_s, 10);  // sorted by time
  EXPECT_EQ(list[0].drone, 0);
  EXPECT_EQ(list[0].kind, FaultKind::battery_drop);
  EXPECT_DOUBLE_EQ(list[0].soc, 0.25);
  EXPECT_EQ(list[1].drone, 1);
  EXPECT_DOUBLE_EQ(list[1].duration_s, 5);
  auto error = [&](const std::string& text) {
    try {
      parse_faults(text, "f.yaml", names, 3600);
    } catch (const base::InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(error("- {t_s: 1, drone: alpha, kind: meteor}\n").find("unknown fault kind \"meteor\""),
            std::string::npos);
  EXPECT_NE(error("- {t_s: 1, drone: zulu, kind: link_loss}\n")
                .find("no drone \"zulu\" in the fleet (alpha, bravo)"),
            std::string::npos);
  EXPECT_NE(error("- {t_s: 1, drone: alpha, kind: battery_drop}\n").find("needs soc"),
            std::string::npos);
  EXPECT_NE(error("- {t_s: -1, drone: alpha, kind: link_loss}\n").find("t_s"), std::string::npos);
  EXPECT_NE(error("- {t_s: 1, drone: alpha, kind: link_loss, colour: red}\n").find("colour"),
            std::string::npos);
  // Random faults: a Poisson process per drone, its own stream: adding a drone leaves alpha's
  // faults as they were; the count over a long horizon is the rate's within 5 sigma.
  const auto two =
      parse_faults("random: {per_drone_per_hour: 30, seed: 9}\n", "f.yaml", names, 36000);
  const auto three = parse_faults("random: {per_drone_per_hour: 30, seed: 9}\n", "f.yaml",
                                  {"alpha", "bravo", "charlie"}, 36000);
  std::vector<double> a2, a3;
  for (const auto& f : two)
    if (f.drone == 0) a2.push_back(f.t_s);
  for (const auto& f : three)
    if (f.drone == 0) a3.push_back(f.t_s);
  EXPECT_EQ(a2, a3);
  const double expected = 30.0 * 10 * 3;  // 3 drones × 10 h × 30 per hour
  EXPECT_NEAR(static_cast<double>(three.size()), expected, 5 * std::sqrt(expected));
}

}  // namespace
}  // namespace swath::fleet
