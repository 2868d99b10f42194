// Trace replay (docs/swath-fleet.md, the paper's level-1 simulator) against a second method: where
// the task graph does not depend on the schedule (cases 1, 3, 4: sensor noise is a hash of the
// place, not of the time), replaying one run's dtg.json with another scheduler and fleet must give
// what re-running the app in its world with that scheduler and fleet gives — the same events, byte
// for byte. Recorded cancels fire again; a graph without scripts is refused.
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <tuple>

#include "swath/base/input_error.hpp"
#include "swath/fleet/apps.hpp"
#include "swath/fleet/dtg.hpp"
#include "swath/fleet/runtime.hpp"
#include "swath/fleet/trace_replay.hpp"
#include "swath/worlds/worlds.hpp"

// Its own namespace: the fleet tests are one unity build, with helpers of the same names.
namespace swath::fleet::trace_replay_test {
namespace {

DroneSpec drone(const std::string& name, Vec3 home = {}) {
  DroneSpec d;
  d.drone.name = name;
  d.home_m = home;
  return d;
}

const App& app_named(const std::string& name) {
  static const std::vector<App> apps = fleet::builtin_apps();
  for (const App& a : apps)
    if (a.name == name) return a;
  throw std::logic_error("no app " + name);
}

// Each task's kind, first place, outcome and action count, as a multiset (ids aside).
std::map<std::tuple<std::string, std::string, std::string, int>, int> task_set(
    const std::string& dtg_json) {
  std::map<std::tuple<std::string, std::string, std::string, int>, int> out;
  const auto graph = nlohmann::json::parse(dtg_json);  // named: a range over a temporary dangles
  for (const auto& n : graph["nodes"])
    if (n["type"] == "task")
      ++out[{n["kind"].get<std::string>(), n.contains("first_loc") ? n["first_loc"].dump() : "",
             n["status"].get<std::string>(), n["actions"].get<int>()}];
  return out;
}

struct Setting {
  std::string scheduler;
  int drones;
};

TEST(TraceReplay, ReproducesTheWorldRunWhereTheGraphDoesNotDependOnTheSchedule) {
  // Recorded: sa with two drones. Replayed with each scheduler and fleet size against the app
  // itself re-run that way (world replay): the two methods must agree exactly.
  const std::vector<std::pair<std::string, std::string>> cases{
      {"road", "road"}, {"hotspot", "hotspot"}, {"multiplexing", "sites"}};
  const std::vector<Setting> settings{{"sa", 2}, {"sa", 1}, {"greedy", 2}, {"round-robin", 3}};
  int compared = 0;
  for (const auto& [name, kind] : cases)
    for (const std::uint64_t seed : {3u, 8u}) {
      const auto world =
          worlds::parse_world("kind: " + kind + "\nseed: " + std::to_string(seed) + "\n", "w.yaml");
      const std::vector<DroneSpec> fleet3{drone("a"), drone("b", {10, 0, 0}),
                                          drone("c", {0, 10, 0})};
      RuntimeSettings s;
      s.app_name = name;
      s.seed = seed;
      const RunRecord recorded =
          run_app(app_named(name), *world, {fleet3.begin(), fleet3.begin() + 2}, s);
      ASSERT_TRUE(recorded.completed) << name << ": " << recorded.failure;
      const App trace = make_trace_app(parse_dtg(recorded.dtg_json, "dtg.json"));
      for (const Setting& st : settings) {
        RuntimeSettings r = s;
        r.scheduler = st.scheduler;
        const std::vector<DroneSpec> fleet(fleet3.begin(), fleet3.begin() + st.drones);
        const RunRecord world_run = run_app(app_named(name), *world, fleet, r);
        const RunRecord replay = run_app(trace, *world, fleet, r);
        const std::string what = name + " seed " + std::to_string(seed) + " " + st.scheduler + " " +
                                 std::to_string(st.drones);
        ASSERT_TRUE(replay.completed) << what << ": " << replay.failure;
        EXPECT_EQ(task_set(replay.dtg_json), task_set(world_run.dtg_json)) << what;
        EXPECT_EQ(replay.completion_time_s, world_run.completion_time_s) << what;
        EXPECT_EQ(replay.events_jsonl, world_run.events_jsonl) << what;
        ++compared;
      }
    }
  EXPECT_EQ(compared, 24);
}

TEST(TraceReplay, ReplaysItsOwnRecordingByteForByte) {
  // The replay's own dtg.json holds the same scripts, so a replay of a replay is the same run.
  const auto world = worlds::parse_world("kind: hotspot\nseed: 5\n", "w.yaml");
  RuntimeSettings s;
  s.app_name = "hotspot";
  const std::vector<DroneSpec> fleet{drone("a"), drone("b", {10, 0, 0})};
  const RunRecord recorded = run_app(app_named("hotspot"), *world, fleet, s);
  const RunRecord once =
      run_app(make_trace_app(parse_dtg(recorded.dtg_json, "a")), *world, fleet, s);
  const RunRecord twice = run_app(make_trace_app(parse_dtg(once.dtg_json, "b")), *world, fleet, s);
  EXPECT_EQ(once.dtg_json, recorded.dtg_json);
  EXPECT_EQ(twice.events_jsonl, recorded.events_jsonl);
}

// Every way a task fails replays as it happened (the tester's fence case: three fly_tos refused
// at the fence came back as task_done at 0.0 s, their scripts empty): a call refused at the
// fence or out of reach, a task awaiting one that failed (`after`), a same_drone task whose drone
// is lost, a request no drone is left to take. Replayed with the run's own settings, the run byte
// for byte: its events and its dtg.json.
TEST(TraceReplay, TasksThatFailedReplayAsTheyFailed) {
  RuntimeSettings s;
  s.app_name = "static";
  s.no_feasible_s = 60;
  // A U (x -50..250, y -50..250 but for a notch x 50..150 above y 50) and a square no drone's
  // home is in.
  s.envelope.inclusions = {
      {{-50, -50}, {250, -50}, {250, 250}, {150, 250}, {150, 50}, {50, 50}, {50, 250}, {-50, 250}},
      {{400, -50}, {450, -50}, {450, 50}, {400, 50}}};
  s.faults = {{.t_s = 60, .drone = 0, .kind = FaultKind::motor_failure},
              {.t_s = 60, .drone = 1, .kind = FaultKind::motor_failure}};
  const auto world = worlds::parse_world(
      "kind: static\nsensors: {camera: {time_s: 2.0}}\ntasks:\n"
      "  - {name: out, actions: [{fly_to: {x_m: 300, y_m: 0}}, {sense: camera}]}\n"
      "  - {name: notch, actions: [{fly_to: {x_m: 100, y_m: 100}}]}\n"
      "  - {name: far, actions: [{fly_to: {x_m: 420, y_m: 0}}, {sense: camera}]}\n"
      "  - {name: next, after: [out], actions: [{fly_to: {x_m: 20, y_m: 20}}]}\n"
      "  - {name: near, actions: [{fly_to: {x_m: 0, y_m: 20}}, {sense: camera}]}\n"
      "  - name: pinned\n    same_drone: true\n    actions:\n"
      "      - fly_to: {x_m: 0, y_m: 150}\n      - hover: 60\n      - fly_to: {x_m: 0, y_m: 200}\n"
      "  - name: late\n    after: [near]\n    actions:\n"
      "      - fly_to: {x_m: 200, y_m: 0}\n      - hover: 60\n",
      "w.yaml");
  const std::vector<DroneSpec> fleet{drone("a"), drone("b", {10, 0, 0})};
  const RunRecord recorded = run_app(app_named("static"), *world, fleet, s);
  ASSERT_TRUE(recorded.completed) << recorded.failure;
  std::map<std::string, int> reasons;  // each failure's kind, from the recorded events
  for (std::size_t at = 0;
       (at = recorded.events_jsonl.find("\"task_failed\"", at)) != std::string::npos; ++at) {
    const auto e = nlohmann::json::parse(recorded.events_jsonl.substr(
        recorded.events_jsonl.rfind('\n', at) + 1,
        recorded.events_jsonl.find('\n', at) - recorded.events_jsonl.rfind('\n', at) - 1));
    const std::string why = e["reason"];
    ++reasons[why.find("outside the inclusion fence") != std::string::npos ? "fence"
              : why.find("out of reach") != std::string::npos              ? "reach"
                                                                           : why];
  }
  // out, and next after it; notch; far; pinned's drone lost; late: no drone left.
  EXPECT_EQ(reasons, (std::map<std::string, int>{
                         {"fence", 3}, {"reach", 1}, {"drone_lost", 1}, {"no_feasible_drone", 1}}));
  const RunRecord replay =
      run_app(make_trace_app(parse_dtg(recorded.dtg_json, "dtg.json")), *world, fleet, s);
  ASSERT_TRUE(replay.completed) << replay.failure;
  EXPECT_EQ(replay.tasks_by_outcome, recorded.tasks_by_outcome);
  EXPECT_EQ(replay.events_jsonl, recorded.events_jsonl);
  EXPECT_EQ(replay.dtg_json, recorded.dtg_json);
}

TEST(TraceReplay, RecordedCancelsFireWithTheirTrigger) {
  // Case 2 cancels cells from inside the cell that made them known: replayed with the recorded
  // scheduler and fleet, the same cells are cancelled, by the same issuers.
  const auto world = worlds::parse_world("kind: rf_field\nseed: 4\n", "w.yaml");
  RuntimeSettings s;
  s.app_name = "wifi";
  const std::vector<DroneSpec> fleet{drone("a"), drone("b", {10, 0, 0})};
  const RunRecord recorded = run_app(app_named("wifi"), *world, fleet, s);
  ASSERT_TRUE(recorded.completed) << recorded.failure;
  ASSERT_GT(recorded.tasks_by_outcome.at("cancelled"), 10);
  const RunRecord replay =
      run_app(make_trace_app(parse_dtg(recorded.dtg_json, "dtg.json")), *world, fleet, s);
  ASSERT_TRUE(replay.completed) << replay.failure;
  EXPECT_EQ(replay.tasks_by_outcome, recorded.tasks_by_outcome);
  const auto edges = [](const std::string& j) {
    std::vector<std::string> out;
    const auto graph = nlohmann::json::parse(j);
    for (const auto& e : graph["edges"])
      if (e["type"] == "cancel") out.push_back(e.dump());
    return out;
  };
  EXPECT_EQ(edges(replay.dtg_json), edges(recorded.dtg_json));
  EXPECT_EQ(task_set(replay.dtg_json), task_set(recorded.dtg_json));

  // A cancel issued after its issuer's reading: the far task is cancelled once the near one is
  // sensed, in the recording and in its replay; a replay with the issuer's reading coming later
  // (a slower fleet) still cancels it at the issuer's reading, not at the recorded time.
  class Flat final : public World {
   public:
    std::string kind() const override { return "flat"; }
    Vec3 start() const override { return {}; }
    double sense_time_s(const std::string&) const override { return 2.0; }
    Reading sense(const std::string& sensor, const Vec3&, double) const override {
      Reading r;
      r.sensor = sensor;
      return r;
    }
  } flat;
  struct Shared {
    TaskHandle<void> far;
  };
  auto shared = std::make_shared<Shared>();
  const App app{"canceller", "", [shared](Ctx& c) -> Co<void> {
                  const Kind far_kind{"far"}, near_kind{"near"};
                  shared->far = c.spawn(far_kind, {}, [](Ctx& t) -> Co<void> {
                    t.fly_to({400, 0, 0});
                    co_await t.sense("x");
                  });
                  auto near = c.spawn(near_kind, {}, [shared](Ctx& t) -> Co<void> {
                    t.fly_to({60, 0, 0});
                    co_await t.sense("x");
                    t.cancel(shared->far);
                  });
                  co_await near;
                  try {
                    co_await shared->far;
                  } catch (const TaskCancelled&) {
                  }
                }};
  RuntimeSettings cs;
  cs.app_name = "canceller";
  const RunRecord rec = run_app(app, flat, {drone("a")}, cs);
  ASSERT_TRUE(rec.completed) << rec.failure;
  ASSERT_EQ(rec.tasks_by_outcome.at("cancelled"), 1);
  const App trace = make_trace_app(parse_dtg(rec.dtg_json, "dtg.json"));
  DroneSpec slow = drone("slow");
  slow.drone.speed_m_s = 2;
  for (const DroneSpec& d : {drone("a"), slow}) {
    const RunRecord rep = run_app(trace, flat, {d}, cs);
    ASSERT_TRUE(rep.completed) << rep.failure;
    EXPECT_EQ(rep.tasks_by_outcome.at("cancelled"), 1) << d.drone.name;
    double near_done = -1, far_cancelled = -2;
    const auto graph = nlohmann::json::parse(rep.dtg_json);
    for (const auto& n : graph["nodes"]) {
      if (n["type"] != "task") continue;
      if (n["kind"] == "near") near_done = n["ended_s"].get<double>();
      if (n["kind"] == "far") {
        EXPECT_EQ(n["status"], "cancelled") << d.drone.name;
        far_cancelled = n["ended_s"].get<double>();
      }
    }
    EXPECT_EQ(far_cancelled, near_done) << d.drone.name;  // with its trigger, whenever that comes
    if (d.drone.name == "slow") {
      EXPECT_GT(near_done,
                nlohmann::json::parse(rec.dtg_json)["nodes"][2]["ended_s"].get<double>());
    }
  }
}

TEST(TraceReplay, RefusesAGraphWithoutScripts) {
  const std::string old =
      R"({"app": "road", "nodes": [{"id": "t0", "type": "task", "kind": "main", "created_s": 0,
      "ended_s": 1, "status": "done"}], "edges": []})";
  EXPECT_THROW(make_trace_app(parse_dtg(old, "old.json")), base::InputError);
  // A script naming an action not queued before its await is no script.
  const std::string bad =
      R"({"app": "x", "nodes": [{"id": "t0", "type": "task", "kind": "main", "created_s": 0,
      "ended_s": 1, "status": "done", "script": [{"await": ["a0"]}]}], "edges": []})";
  EXPECT_THROW(parse_dtg(bad, "bad.json"), base::InputError);
  EXPECT_FALSE(schedule_dependence("wifi").empty());
  EXPECT_TRUE(schedule_dependence("road").empty());
}

}  // namespace
}  // namespace swath::fleet::trace_replay_test
