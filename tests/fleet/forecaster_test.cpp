// The task graph read back and the forecasters (docs/swath-fleet.md) against independent truth:
// dtg.json parsed back equals the JSON read directly; the graph as of a time against a direct
// filter; GMF invariant under rigid motions of the plane (a moved copy of a history is forecast
// exactly, a closed form); constant velocity exact on a straight walk; q against counts made
// directly from the JSON; the held-out scorer against a hand count.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>

#include "swath/base/input_error.hpp"
#include "swath/fleet/apps.hpp"
#include "swath/fleet/dtg.hpp"
#include "swath/fleet/forecaster.hpp"
#include "swath/fleet/runtime.hpp"
#include "swath/vehicle/random.hpp"
#include "swath/worlds/worlds.hpp"

namespace swath::fleet {
namespace {

std::string run_dtg(const std::string& app_name, std::uint64_t seed, int drones = 2) {
  for (const App& app : fleet::builtin_apps()) {
    if (app.name != app_name) continue;
    const auto world = worlds::parse_world(
        "kind: " + fleet::app_world_kind(app.name) + "\nseed: " + std::to_string(seed) + "\n",
        "w.yaml");
    std::vector<DroneSpec> fleet;
    for (int i = 0; i < drones; ++i) {
      DroneSpec d;
      d.drone.name = "d" + std::to_string(i);
      d.home_m = {3.0 * i, 0, 0};
      fleet.push_back(d);
    }
    RuntimeSettings s;
    s.app_name = app.name;
    s.seed = seed;
    s.scheduler = "greedy";
    const RunRecord r = run_app(app, *world, fleet, s);
    EXPECT_TRUE(r.completed) << app_name << " " << seed << ": " << r.failure;
    return r.dtg_json;
  }
  ADD_FAILURE() << "no app " << app_name;
  return {};
}

TEST(Dtg, ParsedBackEqualsTheJsonReadDirectly) {
  for (const char* app : {"hotspot", "wifi", "multiplexing", "road"}) {
    const std::string text = run_dtg(app, 4);
    const Dtg g = parse_dtg(text, "dtg.json");
    const auto j = nlohmann::json::parse(text);
    ASSERT_EQ(g.nodes.size(), j["nodes"].size()) << app;
    ASSERT_EQ(g.edges.size(), j["edges"].size()) << app;
    std::map<std::string, const DtgNode*> by_id;
    for (const DtgNode& n : g.nodes)
      by_id[(n.type == DtgNodeType::task ? "t" : "s") + std::to_string(n.number)] = &n;
    for (const auto& jn : j["nodes"]) {
      const DtgNode& n = *by_id.at(jn["id"].get<std::string>());
      EXPECT_DOUBLE_EQ(n.created_s, jn["created_s"].get<double>());
      if (jn["type"] == "task") {
        EXPECT_EQ(n.kind, jn["kind"]);
        EXPECT_EQ(n.status == DtgStatus::done, jn["status"] == "done");
        EXPECT_EQ(n.status == DtgStatus::cancelled, jn["status"] == "cancelled");
        EXPECT_EQ(n.first_loc_m.has_value(), jn.contains("first_loc"));
        if (n.first_loc_m) {
          EXPECT_DOUBLE_EQ(n.first_loc_m->y, jn["first_loc"][1].get<double>());
        }
      } else {
        EXPECT_EQ(g.nodes.at(static_cast<std::size_t>(n.waiter)).number, jn["waiter"]);
      }
    }
    for (std::size_t e = 0; e < g.edges.size(); ++e) {
      const DtgNode& from = g.nodes[static_cast<std::size_t>(g.edges[e].from)];
      EXPECT_EQ((from.type == DtgNodeType::task ? "t" : "s") + std::to_string(from.number),
                j["edges"][e]["from"]);
    }
  }
}

TEST(Dtg, AsOfKeepsWhatExistedThenAndReopensWhatHadNotEnded) {
  const Dtg g = parse_dtg(run_dtg("hotspot", 2), "dtg.json");
  for (double t : {0.0, 3.3, 17.0, 41.2, 80.0, 1e9}) {
    const Dtg a = g.as_of(t);
    std::size_t expect_nodes = 0, expect_running = 0;
    for (const DtgNode& n : g.nodes) {
      if (n.created_s > t) continue;
      ++expect_nodes;
      if (n.type == DtgNodeType::task && n.ended_s > t) ++expect_running;
    }
    std::size_t running = 0;
    for (const DtgNode& n : a.nodes) {
      EXPECT_LE(n.created_s, t);
      if (n.type == DtgNodeType::task && n.status == DtgStatus::running) {
        ++running;
        EXPECT_TRUE(std::isinf(n.ended_s));
      }
    }
    EXPECT_EQ(a.nodes.size(), expect_nodes) << t;
    EXPECT_EQ(running, expect_running) << t;
    for (const DtgEdge& e : a.edges) {
      ASSERT_LT(static_cast<std::size_t>(e.from), a.nodes.size());
      ASSERT_LT(static_cast<std::size_t>(e.to), a.nodes.size());
    }
  }
  EXPECT_EQ(g.as_of(1e9).edges.size(), g.edges.size());
}

TEST(Dtg, BadInputIsOneSentenceNamingThePlace) {
  const std::string node = R"({"id":"t0","type":"task","kind":"m","created_s":0,"ended_s":1,)"
                           R"("status":"done","actions":0,"drones":[]})";
  const std::pair<std::string, std::string> cases[] = {
      {"[]", "object"},
      {R"({"nodes":[{"id":"x0","type":"task"}],"edges":[]})", "x0"},
      {R"({"nodes":[)" + node + R"(],"edges":[{"from":"t0","to":"t9","type":"spawn"}]})", "to"},
      {R"({"nodes":[)" + node + R"(],"edges":[{"from":"t0","to":"t0","type":"hug"}]})", "hug"},
      {R"({"nodes":[)" + node + "," + node + R"(],"edges":[]})", "second"},
      {R"({"nodes":[{"id":"s0","type":"sync","waiter":4,"created_s":0}],"edges":[]})", "waiter"},
      {R"({"nodes":[)" + node + R"(],"edges":[{"from":"t0","to":"t0","type":"sync"}]})",
       "wrong type"},
  };
  for (const auto& [text, says] : cases) {
    try {
      parse_dtg(text, "runs/a/dtg.json");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const base::InputError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("runs/a/dtg.json"), std::string::npos) << m;
      EXPECT_NE(m.find(says), std::string::npos) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
  }
}

// A walk as an application writes it: main spawns a step, awaits it, spawns the next (road,
// tracking). Step i at `points[i]`, created at 10 i s, ended at 10 i + 8 s.
Dtg walk(const std::vector<vehicle::Vec3>& points, const std::string& kind = "step") {
  Dtg g;
  DtgNode main;
  main.kind = "main";
  main.status = DtgStatus::done;
  main.ended_s = 10.0 * static_cast<double>(points.size()) + 1;
  g.nodes.push_back(main);
  for (std::size_t i = 0; i < points.size(); ++i) {
    DtgNode t;
    t.number = static_cast<int>(i) + 1;
    t.kind = kind;
    t.created_s = 10.0 * static_cast<double>(i);
    t.ended_s = t.created_s + 8;
    t.status = DtgStatus::done;
    t.first_loc_m = points[i];
    g.nodes.push_back(t);
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    DtgNode s;
    s.type = DtgNodeType::sync;
    s.number = static_cast<int>(i);
    s.kind = "main";
    s.waiter = 0;
    s.created_s = 10.0 * static_cast<double>(i);
    g.nodes.push_back(s);
  }
  const int syncs = 1 + static_cast<int>(points.size());
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    g.edges.push_back({i == 0 ? 0 : syncs + i - 1, 1 + i, DtgEdgeType::spawn});
    g.edges.push_back({1 + i, syncs + i, DtgEdgeType::sync});
  }
  return g;
}

std::vector<vehicle::Vec3> random_walk(std::uint64_t seed, int n) {
  auto rng = vehicle::SplitMix64::stream(seed, "walk");
  std::vector<vehicle::Vec3> p{{rng.uniform(-50, 50), rng.uniform(-50, 50), 0}};
  double heading = rng.uniform(0, 2 * std::numbers::pi);
  for (int i = 1; i < n; ++i) {
    heading += rng.uniform(-0.6, 0.6);
    const double step = rng.uniform(3, 9);
    p.push_back({p.back().x + step * std::cos(heading), p.back().y + step * std::sin(heading), 0});
  }
  return p;
}

TEST(Gmf, AMovedCopyOfAHistoryIsForecastExactly) {
  // Rigid motions of the plane leave GMF's ranking unchanged: the run that is a rotated and
  // shifted copy of a history finds it with residual 0 and forecasts its next step moved alike.
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const auto pts = random_walk(seed, 30);
    const double th = 0.7 * static_cast<double>(seed), c = std::cos(th), s = std::sin(th);
    std::vector<vehicle::Vec3> moved;
    for (const auto& p : pts) moved.push_back({c * p.x - s * p.y + 120, s * p.x + c * p.y - 40, 0});
    std::vector<Dtg> histories{walk(random_walk(seed + 100, 30)), walk(pts),
                               walk(random_walk(seed + 200, 30))};
    GmfSettings settings;
    settings.top_k = 1;
    auto gmf = gmf_forecaster(histories, settings);
    const Dtg run = walk(moved);
    for (int i = 1; i + 1 < 30; ++i) {
      const double t = 10.0 * i + 1;
      const auto f = gmf->forecast(run.as_of(t), t);
      ASSERT_EQ(f.size(), 1u) << seed << " step " << i;
      EXPECT_NEAR(f[0].location_m.x, moved[static_cast<std::size_t>(i) + 1].x, 1e-6) << i;
      EXPECT_NEAR(f[0].location_m.y, moved[static_cast<std::size_t>(i) + 1].y, 1e-6) << i;
      EXPECT_DOUBLE_EQ(f[0].p, 1.0);
      EXPECT_NEAR(f[0].expected_s, 10.0 * (i + 1), 1e-9);
      EXPECT_EQ(f[0].kind, "step");
    }
  }
}

TEST(Gmf, WithoutHistoryItLearnsFromTheRunItselfAndNeverForecastsFromTheFrontier) {
  // A straight walk: the run's own finished steps are candidates; their next steps are one step
  // on, so the forecast is the next point. Nothing is forecast before any step has finished.
  std::vector<vehicle::Vec3> line;
  for (int i = 0; i < 20; ++i) line.push_back({5.0 * i, 2.0 * i, 0});
  auto gmf = gmf_forecaster({});
  const Dtg run = walk(line);
  EXPECT_TRUE(gmf->forecast(run.as_of(1), 1).empty());
  for (int i = 12; i < 19; ++i) {
    const double t = 10.0 * i + 1;
    const auto f = gmf->forecast(run.as_of(t), t);
    ASSERT_FALSE(f.empty()) << i;
    EXPECT_NEAR(f[0].location_m.x, line[static_cast<std::size_t>(i) + 1].x, 1e-6) << i;
    EXPECT_NEAR(f[0].location_m.y, line[static_cast<std::size_t>(i) + 1].y, 1e-6) << i;
    EXPECT_DOUBLE_EQ(f[0].p, 1.0);
  }
}

TEST(ConstantVelocity, ExactOnAStraightWalkSilentWithOneBatchOrBetweenBatches) {
  std::vector<vehicle::Vec3> line;
  for (int i = 0; i < 10; ++i) line.push_back({3.0 * i, -4.0 * i, 0});
  auto cv = constant_velocity_forecaster();
  const Dtg run = walk(line);
  EXPECT_TRUE(cv->forecast(run.as_of(1), 1).empty());  // one batch: no displacement yet
  for (int i = 1; i + 1 < 10; ++i) {
    const double t = 10.0 * i + 1;
    const auto f = cv->forecast(run.as_of(t), t);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_NEAR(f[0].location_m.x, 3.0 * (i + 1), 1e-9);
    EXPECT_NEAR(f[0].location_m.y, -4.0 * (i + 1), 1e-9);
  }
  // Between batches (the newest ended, the next not yet spawned) it says nothing.
  EXPECT_TRUE(cv->forecast(run.as_of(29), 29).empty());
}

TEST(Forecasts, TheScorerMeasuresTheNearestConfidentForecastOfTheKind) {
  // Constant velocity on a walk that turns once: every step is forecast exactly but the second
  // (one batch seen: no displacement yet) and the first after the turn (off by the turn's chord).
  std::vector<vehicle::Vec3> pts;
  for (int i = 0; i < 6; ++i) pts.push_back({4.0 * i, 0, 0});
  for (int i = 1; i <= 4; ++i) pts.push_back({20, 4.0 * i, 0});
  auto cv = constant_velocity_forecaster();
  const ForecastScore s = score_forecasts(*cv, walk(pts));
  ASSERT_EQ(s.distances_m.size(), pts.size() - 1);
  EXPECT_TRUE(std::isinf(s.distances_m[0]));  // step 1: one batch seen
  for (std::size_t i = 1; i < s.distances_m.size(); ++i) {
    const double expect = i == 5 ? std::hypot(4.0, 4.0) : 0.0;  // (24,0) forecast, (20,4) came
    EXPECT_NEAR(s.distances_m[i], expect, 1e-9) << i;
  }
  EXPECT_EQ(s.cancellation_pairs, 0u);  // one step runs at a time: no pair
}

TEST(CancellationModel, EqualsCountsMadeDirectlyFromTheJson) {
  // The Wi-Fi app cancels cells the map already knows: q(i→j) by 1 m bin against a count over
  // the raw JSON of other runs (done i; located j created by i's end, not ended before it;
  // cancelled by an edge from i or from a sync node awaiting i).
  std::vector<std::string> texts;
  for (std::uint64_t seed : {11u, 12u}) texts.push_back(run_dtg("wifi", seed, 1));
  std::map<long, std::pair<long, long>> bins;  // bin → (cancelled, trials)
  long c_all = 0, n_all = 0;
  for (const std::string& text : texts) {
    const auto j = nlohmann::json::parse(text);
    std::map<std::string, nlohmann::json> task;
    std::map<std::string, std::vector<std::string>> awaiting;  // task → sync nodes
    std::set<std::pair<std::string, std::string>> cancel;
    for (const auto& n : j["nodes"])
      if (n["type"] == "task") task[n["id"].get<std::string>()] = n;
    for (const auto& e : j["edges"]) {
      const auto from = e["from"].get<std::string>(), to = e["to"].get<std::string>();
      if (e["type"] == "sync") awaiting[from].push_back(to);
      if (e["type"] == "cancel") cancel.insert({from, to});
    }
    for (const auto& [ia, a] : task) {
      if (a["status"] != "done" || !a.contains("first_loc")) continue;
      for (const auto& [ib, b] : task) {
        if (ia == ib || !b.contains("first_loc")) continue;
        const double end = a["ended_s"];
        const double bend = b["ended_s"].get<double>() < 0 ? 1e18 : b["ended_s"].get<double>();
        if (!(b["created_s"].get<double>() <= end && bend >= end)) continue;
        bool by = cancel.count({ia, ib}) > 0;
        for (const auto& s : awaiting[ia]) by |= cancel.count({s, ib}) > 0;
        const double d =
            std::hypot(b["first_loc"][0].get<double>() - a["first_loc"][0].get<double>(),
                       b["first_loc"][1].get<double>() - a["first_loc"][1].get<double>());
        auto& [c, n] = bins[static_cast<long>(d)];
        ++n, ++n_all;
        if (by) ++c, ++c_all;
      }
    }
  }
  ASSERT_GT(c_all, 0) << "the Wi-Fi runs cancelled nothing";
  CancellationModel q;
  for (const std::string& text : texts) q.learn(parse_dtg(text, "dtg.json"));
  const double rate = (static_cast<double>(c_all) + 1.0) / (static_cast<double>(n_all) + 2.0);
  for (const auto& [bin, cn] : bins)
    EXPECT_NEAR(q.q("wifi-cell", "wifi-cell", static_cast<double>(bin) + 0.5),
                (static_cast<double>(cn.first) + rate) / (static_cast<double>(cn.second) + 1.0),
                1e-12)
        << bin;
  EXPECT_NEAR(q.q("wifi-cell", "wifi-cell", 9000), rate, 1e-12);  // beyond every bin: the rate
  EXPECT_EQ(q.q("wifi-cell", "photo", 3), 0.0);                   // never seen: 0
}

TEST(Forecasts, SameHistoriesSameForecasts) {
  std::vector<Dtg> h;
  for (std::uint64_t seed = 1; seed <= 4; ++seed)
    h.push_back(parse_dtg(run_dtg("hotspot", seed, 1), "dtg.json"));
  const Dtg run = parse_dtg(run_dtg("hotspot", 9, 1), "dtg.json");
  auto a = gmf_forecaster(h);
  auto b = gmf_forecaster(h);
  const ForecastScore sa = score_forecasts(*a, run), sb = score_forecasts(*b, run);
  ASSERT_EQ(sa.distances_m.size(), sb.distances_m.size());
  ASSERT_GT(sa.distances_m.size(), 30u);  // 10 squares of 4 corners, the first one unscored
  for (std::size_t i = 0; i < sa.distances_m.size(); ++i)
    EXPECT_EQ(sa.distances_m[i], sb.distances_m[i]);
}

}  // namespace
}  // namespace swath::fleet
