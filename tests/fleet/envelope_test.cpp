// The safety envelope (docs/swath-fleet.md, "Safety envelope") and the checker's rules R9–R13:
// real runs judged by the checker that reads only events.jsonl, each rule seen to catch a
// planted breach of a real log; separation and ceiling measured on whole runs of every app.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "swath/base/input_error.hpp"
#include "swath/fleet/apps.hpp"
#include "swath/fleet/envelope.hpp"
#include "swath/fleet/event_check.hpp"
#include "swath/fleet/fleet_file.hpp"
#include "swath/fleet/runtime.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/worlds/worlds.hpp"

namespace swath::fleet {
namespace {

using json = nlohmann::json;

App app_named(const std::string& name) {
  for (App& a : builtin_apps())
    if (a.name == name) return a;
  ADD_FAILURE() << "no app " << name;
  return {};
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}
std::string join(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& l : v) out += l + "\n";
  return out;
}
std::set<std::string> rules_broken(const std::vector<std::string>& v) {
  std::set<std::string> rules;
  for (const auto& x : check_events(join(v)).violations) rules.insert(x.rule);
  return rules;
}

std::vector<DroneSpec> drones_in_a_row(int n, double spacing_m) {
  std::vector<DroneSpec> out(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    out[static_cast<std::size_t>(i)].drone.name = "d" + std::to_string(i);
    out[static_cast<std::size_t>(i)].home_m = {spacing_m * i, 0, 0};
  }
  return out;
}

// A static world: task a is same_drone with two legs, b has two legs, c one.
const char* kStaticWorld =
    "kind: static\ntasks:\n"
    "  - {name: a, same_drone: true, actions: [{fly_to: {x_m: 30, y_m: 0}}, {sense: cam},"
    " {fly_to: {x_m: 0, y_m: 40}}, {hover: 3}]}\n"
    "  - {name: b, actions: [{fly_to: {x_m: -20, y_m: 5}}, {hover: 2},"
    " {fly_to: {x_m: -30, y_m: 5}}, {sense: cam}]}\n"
    "  - {name: c, actions: [{fly_to: {x_m: 10, y_m: -30}}, {sense: cam}]}\n";

RunRecord static_run(const std::string& world_text, const RuntimeSettings& s, int drones = 3) {
  const auto world = worlds::parse_world(world_text, "w.yaml");
  return run_app(app_named("static"), *world, drones_in_a_row(drones, 5), s);
}

// R10: a same_drone task's second leg moved to another drone in the log (its dispatch and its
// result) is caught; the real log passes.
TEST(EventCheck, SameDroneLegMovedToAnotherDroneFails) {
  RuntimeSettings s;
  s.app_name = "static";
  const RunRecord r = static_run(kStaticWorld, s);
  ASSERT_TRUE(r.completed) << r.failure;
  const EventCheck real = check_events(r.events_jsonl);
  ASSERT_TRUE(real.ok()) << real.violations.front().rule << " " << real.violations.front().message;
  std::vector<std::string> v = lines_of(r.events_jsonl);
  long long task = -1;
  for (const auto& l : v) {
    const json e = json::parse(l);
    if (e["ev"] == "task_created" && e.value("same_drone", false)) task = e["task"];
  }
  ASSERT_GE(task, 0) << "task_created logs same_drone";
  // The results of the task: the last one (its second leg's hover) moved to another drone.
  std::size_t last = 0;
  long long drone = -1;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const json e = json::parse(v[i]);
    if (e["ev"] == "action_done" && e["task"] == task) last = i, drone = e["drone"];
  }
  ASSERT_GT(last, 0u);
  json moved = json::parse(v[last]);
  moved["drone"] = (drone + 1) % 3;
  v[last] = moved.dump();
  EXPECT_TRUE(rules_broken(v).count("R10"));
}

// R9: every segment is announced with its own index and dispatched under it; fairness counts
// each segment's wait from its own announcement.
TEST(EventCheck, EverySegmentIsAnnouncedAndDispatchedUnderItsOwnIndex) {
  RuntimeSettings s;
  s.app_name = "static";
  const RunRecord r = static_run(kStaticWorld, s);
  std::map<long long, std::set<long long>> announced, dispatched;
  for (const auto& l : lines_of(r.events_jsonl)) {
    const json e = json::parse(l);
    if (e["ev"] == "request_visible") announced[e["task"]].insert(e["segment"].get<long long>());
    if (e["ev"] == "dispatch") dispatched[e["task"]].insert(e["segment"].get<long long>());
  }
  // Tasks a and b have two legs each: segments 0 and 1 both announced and dispatched.
  int two_legged = 0;
  for (const auto& [task, segs] : announced)
    if (segs == std::set<long long>{0, 1}) {
      ++two_legged;
      EXPECT_EQ(dispatched[task], segs) << "task " << task;
    }
  EXPECT_EQ(two_legged, 2);
  // A dispatch of segment 1 relabelled 0 (the old log's habit) is caught.
  std::vector<std::string> v = lines_of(r.events_jsonl);
  for (auto& l : v) {
    json e = json::parse(l);
    if (e["ev"] == "dispatch" && e["segment"] == 1) {
      e["segment"] = 0;
      l = e.dump();
      break;
    }
  }
  EXPECT_TRUE(rules_broken(v).count("R9"));
}

// R11: two airborne drones placed within the separation at one drone_state time are caught.
TEST(EventCheck, TwoAirborneDronesWithinTheSeparationFail) {
  RuntimeSettings s;
  s.app_name = "static";
  const RunRecord r = static_run(kStaticWorld, s);
  std::vector<std::string> v = lines_of(r.events_jsonl);
  ASSERT_TRUE(check_events(r.events_jsonl).ok());
  // The first drone_state time with two drones airborne: the second put 3 m from the first.
  for (std::size_t i = 0; i + 1 < v.size(); ++i) {
    json a = json::parse(v[i]), b = json::parse(v[i + 1]);
    if (a["ev"] != "drone_state" || b["ev"] != "drone_state" || a["t_s"] != b["t_s"] ||
        !(a["alt_m"].get<double>() > 0) || !(b["alt_m"].get<double>() > 0))
      continue;
    b["x_m"] = a["x_m"].get<double>() + 3;
    b["y_m"] = a["y_m"];
    b["alt_m"] = a["alt_m"];
    v[i + 1] = b.dump();
    EXPECT_TRUE(rules_broken(v).count("R11"));
    return;
  }
  FAIL() << "no time with two drones airborne";
}

// R12 and R13: a position above the ceiling, outside the inclusion fence, inside an exclusion.
TEST(EventCheck, CeilingAndFenceBreachesFail) {
  RuntimeSettings s;
  s.app_name = "static";
  s.envelope.inclusions = {{{-100, -100}, {100, -100}, {100, 100}, {-100, 100}}};
  s.envelope.exclusions = {{{60, 60}, {80, 60}, {80, 80}, {60, 80}}};
  const RunRecord r = static_run(kStaticWorld, s);
  ASSERT_TRUE(r.completed) << r.failure;
  ASSERT_TRUE(check_events(r.events_jsonl).ok());
  const std::vector<std::string> lines = lines_of(r.events_jsonl);
  std::size_t state = 0;
  for (std::size_t i = 0; i < lines.size() && !state; ++i)
    if (lines[i].find("\"drone_state\"") != std::string::npos) state = i;
  const auto with = [&](double x, double y, double z) {
    std::vector<std::string> v = lines;
    json e = json::parse(v[state]);
    e["x_m"] = x, e["y_m"] = y, e["alt_m"] = z;
    v[state] = e.dump();
    return rules_broken(v);
  };
  EXPECT_TRUE(with(0, 0, 121).count("R12"));
  EXPECT_FALSE(with(0, 0, 119).count("R12"));
  EXPECT_TRUE(with(150, 0, 20).count("R13"));  // outside the inclusion
  EXPECT_TRUE(with(70, 70, 20).count("R13"));  // inside the exclusion
  EXPECT_FALSE(with(50, 50, 20).count("R13"));
}

// R13 on the leg between two logged positions: a drone that crosses a 2 m exclusion strip, or
// cuts across a U-shaped inclusion's notch, between two samples 1 s apart breaks it though both
// samples lie inside the envelope.
TEST(EventCheck, ALegBetweenSamplesThroughTheFenceFails) {
  const std::string start =
      R"({"t_s":0,"ev":"run_start","drones":[{"drone":0,"soc":1}],"envelope":{"ceiling_m":120,)"
      R"("separation_m":5,"inclusions":[[[-50,-50],[250,-50],[250,250],[150,250],[150,50],)"
      R"([50,50],[50,250],[-50,250]]],"exclusions":[[[100,-40],[102,-40],[102,40],[100,40]]]}})";
  const auto flight = [&](std::array<double, 2> a, std::array<double, 2> b) {
    const auto state = [](double t_s, std::array<double, 2> p) {
      return json{{"t_s", t_s},  {"ev", "drone_state"}, {"drone", 0}, {"x_m", p[0]},
                  {"y_m", p[1]}, {"alt_m", 20},         {"soc", 0.9}, {"state", "flying"}}
          .dump();
    };
    const std::vector<std::string> v = {start, state(1, a), state(2, b),
                                        R"({"t_s":3,"ev":"run_end"})"};
    return check_events(join(v));
  };
  const EventCheck across_strip = flight({95, 0}, {105, 0});
  ASSERT_EQ(across_strip.violations.size(), 1U);
  EXPECT_EQ(across_strip.violations[0].rule, "R13");
  EXPECT_NE(across_strip.violations[0].message.find("inside an exclusion fence"), std::string::npos)
      << across_strip.violations[0].message;
  EXPECT_TRUE(flight({95, 0}, {99, 0}).ok());     // beside the strip, along it
  EXPECT_TRUE(flight({95, 45}, {105, 45}).ok());  // past the strip's end
  const EventCheck across_notch = flight({40, 200}, {160, 200});
  ASSERT_EQ(across_notch.violations.size(), 1U);
  EXPECT_NE(across_notch.violations[0].message.find("outside the inclusion fence"),
            std::string::npos)
      << across_notch.violations[0].message;
  EXPECT_TRUE(flight({40, 200}, {40, 0}).ok());  // down the U's left arm
  // A forecast place in the strip, sent to but not yet reached, breaks it too.
  const std::vector<std::string> sent = {
      start, R"({"t_s":1,"ev":"position","drone":0,"x_m":101,"y_m":0,"alt_m":20,"p":1})",
      R"({"t_s":2,"ev":"run_end"})"};
  const EventCheck c = check_events(join(sent));
  ASSERT_EQ(c.violations.size(), 1U);
  EXPECT_EQ(c.violations[0].message, "a forecast place inside an exclusion fence");
}

// Targets outside the envelope are errors to the app, never flown: above the ceiling, outside
// the inclusion fence, inside an exclusion; the rest of the app goes on.
TEST(Envelope, TargetsOutsideTheEnvelopeAreRefusedNeverFlown) {
  RuntimeSettings s;
  s.app_name = "static";
  s.envelope.inclusions = {{{-100, -100}, {100, -100}, {100, 100}, {-100, 100}}};
  s.envelope.exclusions = {{{60, 60}, {80, 60}, {80, 80}, {60, 80}}};
  const std::string world =
      "kind: static\ntasks:\n"
      "  - {name: high, actions: [{fly_to: {x_m: 10, y_m: 0, alt_m: 200}}]}\n"
      "  - {name: out, actions: [{fly_to: {x_m: 300, y_m: 0}}]}\n"
      "  - {name: excl, actions: [{fly_to: {x_m: 70, y_m: 70}}]}\n"
      "  - {name: fine, actions: [{fly_to: {x_m: 20, y_m: 20, alt_m: 40}}, {sense: cam}]}\n";
  const RunRecord r = static_run(world, s);
  const EventCheck c = check_events(r.events_jsonl);
  EXPECT_TRUE(c.ok()) << c.violations.front().rule << " " << c.violations.front().message;
  int failed = 0, done = 0;
  for (const auto& l : lines_of(r.events_jsonl)) {
    const json e = json::parse(l);
    if (e["ev"] == "dispatch") {
      EXPECT_LT(std::abs(e["x_m"].get<double>()), 100);
      EXPECT_LE(e["alt_m"].get<double>(), 120);
    }
    if (e["ev"] == "task_failed") ++failed;
    if (e["ev"] == "task_done") ++done;
  }
  EXPECT_EQ(failed, 3);
  EXPECT_GE(done, 1);
  EXPECT_LE(c.max_altitude_m, 120);
}

// The tester's U-shaped inclusion: x -50..250, y -50..250 but for a notch x 50..150 above y 50.
const std::vector<std::vector<std::array<double, 2>>> kUFence = {
    {{-50, -50}, {250, -50}, {250, 250}, {150, 250}, {150, 50}, {50, 50}, {50, 250}, {-50, 250}}};

std::vector<json> events_named(const std::string& jsonl, const std::string& ev) {
  std::vector<json> out;
  for (const auto& l : lines_of(jsonl))
    if (const json e = json::parse(l); e["ev"] == ev) out.push_back(e);
  return out;
}

// Legs are straight: a drone waiting at a (left arm) is not sent across the notch to c (right
// arm); the drone whose home lies under c flies it. The checker judges every leg between logged
// positions, so a crossing would break R13.
TEST(Envelope, NoLegCrossesTheFenceBetweenItsEnds) {
  RuntimeSettings s;
  s.app_name = "static";
  s.envelope.inclusions = kUFence;
  const std::string text =
      "kind: static\ntasks:\n"
      "  - {name: a, actions: [{fly_to: {x_m: 0, y_m: 200}}, {hover: 2}]}\n"
      "  - {name: c, after: [a], actions: [{fly_to: {x_m: 200, y_m: 200}}, {hover: 2}]}\n";
  std::vector<DroneSpec> drones = drones_in_a_row(2, 0);
  drones[1].home_m = {200, -40, 0};
  const RunRecord r = run_app(app_named("static"), *worlds::parse_world(text, "w.yaml"), drones, s);
  ASSERT_TRUE(r.completed) << r.failure;
  const EventCheck c = check_events(r.events_jsonl);
  for (const auto& v : c.violations) ADD_FAILURE() << v.line << " " << v.rule << " " << v.message;
  int to_c = 0;
  for (const json& e : events_named(r.events_jsonl, "dispatch"))
    if (e["x_m"].get<double>() > 150) {
      EXPECT_EQ(e["drone"], 1) << e.dump();
      ++to_c;
    }
  EXPECT_EQ(to_c, 1);
}

// An L-shaped field: x 0..200 along y 0..60, and x 0..60 up to y 200; an exclusion at
// x 100..120, y 20..40; a second inclusion apart from it at x 300..340.
const std::vector<std::vector<std::array<double, 2>>> kLFence = {
    {{0, 0}, {200, 0}, {200, 60}, {60, 60}, {60, 200}, {0, 200}},
    {{300, 0}, {340, 0}, {340, 40}, {300, 40}}};

// Every position a drone logged (drone_mode, drone_state), as x, y.
std::vector<std::array<double, 2>> logged_positions(const std::string& jsonl) {
  std::vector<std::array<double, 2>> out;
  for (const auto& l : lines_of(jsonl))
    if (const json e = json::parse(l);
        (e["ev"] == "drone_mode" || e["ev"] == "drone_state") && e.contains("x_m"))
      out.push_back({e["x_m"].get<double>(), e["y_m"].get<double>()});
  return out;
}

// A target round the L's corner is reached by the way round it, stop by stop, and the way home
// likewise (sent home by a battery drop there): every logged position inside the fence, every
// leg between them too (the checker's R13), the target visited. A target outside the fence, in an
// exclusion, or in an inclusion no home reaches fails at once, saying why.
TEST(Envelope, ATargetRoundTheFencesCornerIsReachedByTheWayRoundIt) {
  RuntimeSettings s;
  s.app_name = "static";
  s.envelope.inclusions = kLFence;
  s.envelope.exclusions = {{{100, 20}, {120, 20}, {120, 40}, {100, 40}}};
  s.faults = {{50, 0, FaultKind::battery_drop, 10, 0.2}};  // in the hover at the far arm's end
  const std::string text =
      "kind: static\ntasks:\n"
      "  - {name: round, actions: [{fly_to: {x_m: 20, y_m: 180}}, {hover: 30}]}\n"
      "  - {name: out, actions: [{fly_to: {x_m: 150, y_m: 150}}]}\n"
      "  - {name: ex, actions: [{fly_to: {x_m: 110, y_m: 30}}]}\n"
      "  - {name: island, actions: [{fly_to: {x_m: 320, y_m: 20}}]}\n";
  std::vector<DroneSpec> drones = drones_in_a_row(1, 0);
  drones[0].home_m = {180, 20, 0};
  const RunRecord r = run_app(app_named("static"), *worlds::parse_world(text, "w.yaml"), drones, s);
  const EventCheck c = check_events(r.events_jsonl);
  for (const auto& v : c.violations) ADD_FAILURE() << v.line << " " << v.rule << " " << v.message;
  LocalEnvelope fence;
  fence.inclusions = s.envelope.inclusions;
  fence.exclusions = s.envelope.exclusions;
  bool visited = false;
  const auto positions = logged_positions(r.events_jsonl);
  for (const auto& [x, y] : positions) {
    EXPECT_EQ(fence.refusal_xy(x, y), "") << x << " " << y;
    visited = visited || std::hypot(x - 20, y - 180) < 1e-6;
  }
  EXPECT_TRUE(visited);
  // Sent home from the far arm by the battery drop, it lands at home by the way round (R13 above
  // judged each of its legs), then comes back for the hover.
  int charging_at_home = 0;
  for (const json& e : events_named(r.events_jsonl, "drone_mode"))
    if (e["state"] == "charging" && e["at_s"].get<double>() > 50)
      charging_at_home +=
          std::hypot(e["x_m"].get<double>() - 180, e["y_m"].get<double>() - 20) < 1e-6;
  EXPECT_EQ(charging_at_home, 1);
  std::map<std::string, std::string> failed;
  for (const json& e : events_named(r.events_jsonl, "task_failed"))
    failed[std::to_string(e["task"].get<int>())] = e["reason"];
  ASSERT_EQ(failed.size(), 3U) << r.events_jsonl;
  std::string reasons;
  for (const auto& [task, why] : failed) reasons += why + "\n";
  EXPECT_NE(reasons.find("fly_to (150, 150, 0) m is outside the inclusion fence"),
            std::string::npos)
      << reasons;
  EXPECT_NE(reasons.find("fly_to (110, 30, 0) m is inside an exclusion fence"), std::string::npos)
      << reasons;
  EXPECT_NE(reasons.find("fly_to (320, 20, 0) m is out of reach: no way to it inside the fence"),
            std::string::npos)
      << reasons;
  EXPECT_EQ(events_named(r.events_jsonl, "task_done").size(), 2U);  // round and the app's main
}

// Speculative positioning keeps the fence: the place a drone was sent to on a forecast, with an
// exclusion around it, is flown to no more, and every leg of the run stays outside it.
TEST(Envelope, NoDroneIsPositionedAtAForecastPlaceInsideAnExclusion) {
  const auto world = worlds::parse_world("kind: road\nseed: 3\nsteps: 8\n", "w.yaml");
  RuntimeSettings s;
  s.app_name = "road";
  s.forecaster = "constant-velocity";
  s.max_time_s = 1200;
  const RunRecord open = run_app(app_named("road"), *world, drones_in_a_row(3, 5), s);
  const std::vector<json> sent = events_named(open.events_jsonl, "position");
  ASSERT_FALSE(sent.empty());
  const double x = sent[0]["x_m"], y = sent[0]["y_m"];
  s.envelope.exclusions = {{{x - 2, y - 2}, {x + 2, y - 2}, {x + 2, y + 2}, {x - 2, y + 2}}};
  const RunRecord fenced = run_app(app_named("road"), *world, drones_in_a_row(3, 5), s);
  const EventCheck c = check_events(fenced.events_jsonl);
  for (const auto& v : c.violations) ADD_FAILURE() << v.line << " " << v.rule << " " << v.message;
  for (const json& e : events_named(fenced.events_jsonl, "position"))
    EXPECT_GT(std::max(std::abs(e["x_m"].get<double>() - x), std::abs(e["y_m"].get<double>() - y)),
              2)
        << e.dump();
}

// The fleet must fit: 100 drones 5 m apart from 20 m do not fit under 120 m (21 do, 22 do not);
// a home outside the inclusion fence is refused before anything flies.
TEST(Envelope, AFleetThatCannotFitIsRefused) {
  const auto world = worlds::parse_world("kind: rf_field\nseed: 2\n", "w.yaml");
  RuntimeSettings s;
  s.app_name = "wifi";
  s.max_time_s = 1;
  const auto refusal = [&](int n, const RuntimeSettings& st) {
    try {
      run_app(app_named("wifi"), *world, drones_in_a_row(n, 5), st);
    } catch (const base::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(refusal(100, s).find("above the ceiling of 120 m"), std::string::npos);
  EXPECT_NE(refusal(22, s).find("at most 21 drones fit"), std::string::npos);
  EXPECT_EQ(refusal(21, s), "");
  constexpr double kNoFenceHeight = std::numeric_limits<double>::infinity();
  EXPECT_EQ(layers_refusal(21, 20, 5, 120, kNoFenceHeight, false), "");
  EXPECT_NE(layers_refusal(22, 20, 5, 120, kNoFenceHeight, false), "");
  // The limit named is the lower one, and separation_m is offered only where it spaces the layers.
  const std::string ceiling = layers_refusal(2, 20, 5, 24, kNoFenceHeight, false);
  EXPECT_NE(ceiling.find("above the ceiling of 24 m: at most 1 drone fits (raise ceiling_m in"),
            std::string::npos)
      << ceiling;
  const std::string fence = layers_refusal(3, 20, 8, 120, 30, true);
  EXPECT_NE(fence.find("above the fence's max_altitude_m of 30 m: at most 2 drones fit (raise "
                       "the fence's max_altitude_m or lower separation_m in"),
            std::string::npos)
      << fence;
  RuntimeSettings fenced = s;
  fenced.envelope.inclusions = {{{-10, -10}, {8, -10}, {8, 10}, {-10, 10}}};
  EXPECT_NE(refusal(3, fenced).find("d2's home (10.0, 0.0) m is outside the inclusion fence"),
            std::string::npos);
}

// run_start carries the fence, and check and render read lines of at most 1 MiB: the largest
// fence a run flies (20,000 vertices, 20,000 km out: the longest numbers) logs a shorter line, one
// vertex more is refused before anything runs.
TEST(Envelope, AFenceTooLargeForTheLogIsRefused) {
  const auto world = worlds::parse_world("kind: rf_field\nseed: 2\n", "w.yaml");
  RuntimeSettings s;
  s.app_name = "wifi";
  s.max_time_s = 1;
  std::size_t longest_line = 0;
  s.on_event = [&](const std::string& line) { longest_line = std::max(longest_line, line.size()); };
  const double radius_m = 20015086.796021;
  std::vector<std::array<double, 2>> ring;
  for (std::size_t i = 0; i < kMaxFenceVertices; ++i) {
    const double a = 2 * std::acos(-1.0) * static_cast<double>(i) / kMaxFenceVertices;
    ring.push_back({-radius_m * std::cos(a) + 1e-6, -radius_m * std::sin(a) - 1e-6});
  }
  s.envelope.inclusions = {ring};
  const auto refusal = [&]() {
    try {
      run_app(app_named("wifi"), *world, drones_in_a_row(2, 6), s);
    } catch (const base::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(refusal(), "");
  EXPECT_GT(longest_line, std::size_t{500000});  // run_start, with the fence
  EXPECT_LT(longest_line, std::size_t{1} << 20);
  s.envelope.exclusions = {{{1000, 1000}, {1010, 1000}, {1010, 1010}}};
  EXPECT_NE(refusal().find("fence: 20003 vertices; swath-fleet flies a fence of at most 20000"),
            std::string::npos)
      << refusal();
}

// Whole runs of every app with 8 drones: the checker finds no violation (R11 included), the least
// distance between airborne drones is at least the separation, the highest point under the
// ceiling — also with all homes at one point (the take-off rule lets one climb at a time).
TEST(Envelope, EveryAppKeepsItsDronesApartAndUnderTheCeiling) {
  const std::map<std::string, std::string> worlds{
      {"multiplexing", "kind: sites\nseed: 3\n"},
      {"hotspot", "kind: hotspot\nseed: 3\nsteps: 4\n"},
      {"wifi", "kind: rf_field\nseed: 3\n"},
      {"road", "kind: road\nseed: 3\nsteps: 8\n"},
      {"tracking", "kind: tracking\nseed: 3\nduration_s: 120\n"},
      {"static", kStaticWorld}};
  for (const double spacing_m : {5.0, 0.0}) {
    for (const auto& [app, text] : worlds) {
      const auto world = worlds::parse_world(text, "w.yaml");
      RuntimeSettings s;
      s.app_name = app;
      s.max_time_s = 1200;
      const RunRecord r = run_app(app_named(app), *world, drones_in_a_row(8, spacing_m), s);
      const EventCheck c = check_events(r.events_jsonl);
      for (const auto& v : c.violations)
        ADD_FAILURE() << app << " homes " << spacing_m << " m apart: line " << v.line << ": "
                      << v.rule << ": " << v.message;
      EXPECT_GE(c.least_separation_m, 5.0 - 1e-6) << app;
      EXPECT_LE(c.max_altitude_m, 120.0) << app;
      EXPECT_GE(c.max_altitude_m, 20.0) << app;  // something flew
    }
  }
}

// A drone's logged positions (drone_state, drone_mode at its own at_s) in time order: the trace
// a reader of events.jsonl sees; between two of them the drone is taken to fly straight at an
// even pace, as the checker's R13 takes it.
struct Fix {
  double t_s;
  std::array<double, 3> at;
  std::string state;
};
std::map<int, std::vector<Fix>> trace_of(const std::string& events_jsonl) {
  std::map<int, std::vector<Fix>> out;
  for (const auto& l : lines_of(events_jsonl)) {
    const json e = json::parse(l);
    if ((e["ev"] != "drone_state" && e["ev"] != "drone_mode") || e["state"] == "lost") continue;
    const double t_s = e.value("at_s", e["t_s"].get<double>());
    out[e["drone"].get<int>()].push_back({t_s, {e["x_m"], e["y_m"], e["alt_m"]}, e["state"]});
  }
  for (auto& [drone, fixes] : out)
    std::stable_sort(fixes.begin(), fixes.end(),
                     [](const Fix& a, const Fix& b) { return a.t_s < b.t_s; });
  return out;
}
std::array<double, 3> where_at(const std::vector<Fix>& fixes, double t_s) {
  if (t_s <= fixes.front().t_s) return fixes.front().at;
  for (std::size_t i = 1; i < fixes.size(); ++i) {
    if (t_s > fixes[i].t_s) continue;
    const Fix &a = fixes[i - 1], &b = fixes[i];
    const double f = b.t_s > a.t_s ? (t_s - a.t_s) / (b.t_s - a.t_s) : 1.0;
    return {a.at[0] + f * (b.at[0] - a.at[0]), a.at[1] + f * (b.at[1] - a.at[1]),
            a.at[2] + f * (b.at[2] - a.at[2])};
  }
  return fixes.back().at;
}
// The least 3-D distance between two airborne drones of the trace, every 0.01 s.
double least_separation_m(const std::map<int, std::vector<Fix>>& trace, double end_s) {
  double least = 1e9;
  for (double t = 0; t <= end_s; t += 0.01)
    for (auto i = trace.begin(); i != trace.end(); ++i)
      for (auto j = std::next(i); j != trace.end(); ++j) {
        const auto a = where_at(i->second, t), b = where_at(j->second, t);
        if (a[2] > 0 && b[2] > 0)
          least = std::min(least, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
      }
  return least;
}

// The landing is flown, not dropped: drone b (layer 25 m) comes home after p1 while a watch
// waits at (1, 2), 3.6 m across from b's home (4, 0). a (20 m) working there would be in b's way
// down and make it hold (when the landing was instant at home, b passed 3.6 m from it); the
// scheduler gives that place to no drone below b's layer while b is out (scheduler.hpp,
// LandingColumn), so b descends at once over its home, sample by sample in the log, and lands.
// a climbs at 2 m/s (10 s to its layer, b 8.3 s to its own), so b, 4 m nearer, is sent to p1.
TEST(Envelope, ALandingIsFlownAndNoWorkerBelowHoldsIt) {
  const auto world = worlds::parse_world(
      "kind: static\nsensors: {camera: {time_s: 2.0}}\ntasks:\n"
      "  - {name: p1, actions: [{fly_to: {x_m: 40, y_m: 0}}, {sense: camera}]}\n"
      "  - {name: watch, after: [p1], actions: [{fly_to: {x_m: 1, y_m: 2}}, {hover: 40}]}\n"
      "  - {name: away, after: [watch], actions: [{fly_to: {x_m: -40, y_m: 30}}, {hover: 20}]}\n",
      "w.yaml");
  std::vector<DroneSpec> fleet = drones_in_a_row(2, 4);
  fleet[0].max_flight_time_s = 600;
  fleet[0].drone.climb_speed_m_s = 2;
  fleet[1].max_flight_time_s = 70;
  RuntimeSettings s;
  s.app_name = "static";
  const RunRecord r = run_app(app_named("static"), *world, fleet, s);
  ASSERT_TRUE(r.completed) << r.failure;
  const EventCheck c = check_events(r.events_jsonl);
  EXPECT_TRUE(c.ok()) << c.violations.front().rule << " " << c.violations.front().message;
  const auto trace = trace_of(r.events_jsonl);
  EXPECT_GE(least_separation_m(trace, r.end_s), 5.0 - 1e-6);
  // b over its home at 25 m: first when it arrives, last when it starts down; then on the ground.
  double over_from_s = -1, over_to_s = -1, down_s = -1;
  int descending = 0;  // positions logged between the two
  for (const Fix& f : trace.at(1)) {
    if (f.at[0] != 4 || f.at[1] != 0) continue;
    if (f.state == "returning" && f.at[2] == 25) {
      if (over_from_s < 0) over_from_s = f.t_s;
      over_to_s = f.t_s;
    } else if (f.state == "returning" && over_from_s > 0) {
      ++descending;
    } else if (f.state == "charging" && down_s < 0) {
      down_s = f.t_s;
    }
  }
  ASSERT_GT(over_from_s, 0) << "b came home";
  ASSERT_GT(down_s, 0) << "b landed";
  EXPECT_LT(over_to_s - over_from_s, s.tick_s + 1e-9) << "b held over its home";
  EXPECT_NEAR(down_s - over_to_s, 25.0 / fleet[1].kinematics().descent_m_s, 1e-5);
  EXPECT_GE(descending, 7);
}

// Heights change no faster than the drones climb and descend: case 5's short flights from homes
// 1 m apart take off and land again and again; every pair of consecutive positions in the log
// keeps |Δz| within the vertical speed × Δt, every landing is logged on its way down, and the
// airborne drones stay apart between the samples as at them.
TEST(Envelope, HeightsInTheLogChangeNoFasterThanTheVerticalSpeed) {
  const auto world = worlds::parse_world("kind: tracking\nseed: 3\nduration_s: 300\n", "w.yaml");
  std::vector<DroneSpec> fleet = drones_in_a_row(2, 1);
  for (DroneSpec& d : fleet) d.max_flight_time_s = 60, d.recharge_s = 30;
  RuntimeSettings s;
  s.app_name = "tracking";
  const RunRecord r = run_app(app_named("tracking"), *world, fleet, s);
  ASSERT_TRUE(r.completed) << r.failure;
  EXPECT_TRUE(check_events(r.events_jsonl).ok());
  const auto trace = trace_of(r.events_jsonl);
  int landings_seen = 0;
  for (const auto& [drone, fixes] : trace) {
    const Kinematics k = fleet[static_cast<std::size_t>(drone)].kinematics();
    for (std::size_t i = 1; i < fixes.size(); ++i) {
      const double dz = fixes[i].at[2] - fixes[i - 1].at[2], dt = fixes[i].t_s - fixes[i - 1].t_s;
      EXPECT_LE(dz, k.climb_m_s * dt + 1e-5) << "drone " << drone << " at " << fixes[i].t_s;
      EXPECT_LE(-dz, k.descent_m_s * dt + 1e-5) << "drone " << drone << " at " << fixes[i].t_s;
      landings_seen += fixes[i].at[2] == 0 && dz < 0;
    }
  }
  EXPECT_GE(landings_seen, 4);
  EXPECT_GE(least_separation_m(trace, r.end_s), 5.0 - 1e-6);
}

// The fleet file's envelope keys and its GeoJSON fence.
TEST(Envelope, FleetFileKeysAndGeoJsonFence) {
  const auto dir = std::filesystem::temp_directory_path() / "swath-envelope-test";
  std::filesystem::create_directories(dir);
  {
    std::ofstream f(dir / "fence.geojson");
    f << R"({"type":"FeatureCollection","features":[
      {"type":"Feature","properties":{"fence":"inclusion"},"geometry":{"type":"Polygon",
       "coordinates":[[[8.0,47.0],[8.01,47.0],[8.01,47.01],[8.0,47.01],[8.0,47.0]]]}},
      {"type":"Feature","properties":{"fence":"exclusion"},"geometry":{"type":"Polygon",
       "coordinates":[[[8.004,47.004],[8.005,47.004],[8.005,47.005]]]}}]})";
  }
  const std::string fleet =
      "ceiling_m: 90\nseparation_m: 8\nfence: {geojson: fence.geojson, max_altitude_m: 80}\n"
      "drones:\n  - {name: a, speed_m_s: 10}\n  - {name: b, speed_m_s: 10}\n";
  const std::string source = (dir / "fleet.yaml").string();
  const FleetFileContents contents = parse_fleet_file_contents(fleet, source, {47.0, 8.0, 0});
  const Envelope& e = contents.envelope;
  EXPECT_EQ(e.ceiling_m, 90);
  EXPECT_EQ(e.separation_m, 8);
  EXPECT_EQ(e.fence.max_altitude_m, 80);
  ASSERT_EQ(e.fence.polygons.size(), 2u);
  EXPECT_TRUE(e.fence.polygons[0].inclusion);
  EXPECT_EQ(e.fence.polygons[0].ring_deg.size(), 4u);  // closed ring: the repeat dropped
  EXPECT_FALSE(e.fence.polygons[1].inclusion);
  EXPECT_DOUBLE_EQ(e.fence.polygons[1].ring_deg[0].lat_deg, 47.004);
  // Shared homes stand separation_m + 1 m apart: the separation read once serves both.
  const auto& drones = contents.drones;
  ASSERT_EQ(drones.size(), 2u);
  EXPECT_NEAR(drones[1].home_m.x - drones[0].home_m.x, 9, 1e-9);
  // The local envelope: a point at the origin's corner is inside (on the boundary), one west of
  // it outside, the exclusion's middle refused, heights above 80 m refused.
  const LocalEnvelope l = local_envelope(e, {47.0, 8.0, 0});
  EXPECT_EQ(l.refusal({1, 1, 50}), "");
  EXPECT_EQ(l.refusal({-5, 1, 50}), "outside the inclusion fence");
  EXPECT_EQ(l.refusal({1, 1, 85}), "above the fence's 80 m");
  EXPECT_EQ(l.refusal({1, 1, 95}), "above the ceiling of 90 m");
  const geometry::Point2 in_triangle =
      geometry::LocalFrame({47.0, 8.0, 0}).to_local({47.0041, 8.0049, 0});
  EXPECT_EQ(l.refusal_xy(in_triangle.x, in_triangle.y), "inside an exclusion fence");
  const auto error = [&](const std::string& text) {
    try {
      parse_fleet_file_contents(text + "drones: [{name: a, speed_m_s: 10}]\n", source,
                                {47.0, 8.0, 0});
    } catch (const base::InputError& x) {
      return std::string(x.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(error("ceiling_m: -3\n").find("ceiling_m"), std::string::npos);
  EXPECT_NE(error("fence: {max_altitude_m: 3}\n").find("no geojson"), std::string::npos);
  EXPECT_NE(error("fence: {geojson: missing.geojson}\n").find("missing.geojson"),
            std::string::npos);
  {
    std::ofstream f(dir / "line.geojson");
    f << R"({"type":"LineString","coordinates":[[8,47],[8.1,47]]})";
  }
  EXPECT_NE(error("fence: {geojson: line.geojson}\n").find("Polygon or MultiPolygon"),
            std::string::npos);
  std::filesystem::remove_all(dir);
}

// A fence file of the wrong shapes (found by fuzzing: members of another type made the JSON
// library throw its own type_error): each is one InputError naming the file.
TEST(Envelope, MalformedFenceFilesAreInputErrors) {
  for (const std::string text :
       {R"({"type":5})", R"({"type":"FeatureCollection","features":[5]})",
        R"({"type":"FeatureCollection","features":7})", R"({"type":"Feature","geometry":3})",
        R"({"type":"Polygon","coordinates":"x"})", R"({"type":"MultiPolygon","coordinates":4})",
        R"([1,2])", R"({"type":"Feature","properties":{"fence":1},"geometry":null})"}) {
    try {
      parse_fence_geojson(text, "f.geojson");
      ADD_FAILURE() << text << " accepted";
    } catch (const base::InputError& x) {
      EXPECT_EQ(std::string(x.what()).rfind("f.geojson", 0), 0u) << x.what();
    }
  }
}

// A fence polygon that crosses itself (a bow-tie) is refused naming the file, the feature and
// where it crosses, as swath plan refuses such a zone.
TEST(Envelope, ASelfCrossingFencePolygonIsRefusedSayingWhere) {
  const std::string bowtie =
      R"({"type":"FeatureCollection","features":[{"type":"Feature","geometry":{"type":"Polygon",)"
      R"("coordinates":[[[8.0,47.0],[8.01,47.01],[8.01,47.0],[8.0,47.01],[8.0,47.0]]]}}]})";
  try {
    parse_fence_geojson(bowtie, "bow.geojson");
    ADD_FAILURE() << "a bow-tie fence accepted";
  } catch (const base::InputError& x) {
    const std::string m = x.what();
    const std::string head = "bow.geojson: features[0]: the fence polygon crosses itself at ";
    ASSERT_EQ(m.rfind(head, 0), 0U) << m;
    double lat = 0, lon = 0;
    ASSERT_EQ(std::sscanf(m.c_str() + head.size(), "%lf, %lf", &lat, &lon), 2) << m;
    EXPECT_NEAR(lat, 47.005, 1e-4);
    EXPECT_NEAR(lon, 8.005, 1e-4);
  }
}

// summary's faults: those that happened; a fault scheduled after the run ended did not.
TEST(Envelope, FaultsCountedAsTheyHappened) {
  RuntimeSettings s;
  s.app_name = "static";
  s.faults = {{5, 1, FaultKind::link_loss, 3, 0}, {99999, 0, FaultKind::link_loss, 3, 0}};
  const RunRecord r = static_run(kStaticWorld, s);
  const EventCheck c = check_events(r.events_jsonl);
  EXPECT_EQ(r.faults_happened, 1);
  EXPECT_EQ(c.faults, 1);
}

}  // namespace
}  // namespace swath::fleet
