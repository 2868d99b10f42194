// The case-study applications of paper 000 §5, written as the paper writes them (Fig. 1, 3, 6):
// loops over what the drones just measured, so the next request depends on the last reading.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "gaussian_process.hpp"
#include "swath/fleet/apps.hpp"
#include "swath/fleet/leg.hpp"

namespace swath::fleet {

using worlds::HotspotWorld;
using worlds::RfFieldWorld;
using worlds::RoadWorld;
using worlds::SitesWorld;
using worlds::StaticWorld;
using worlds::TrackingWorld;

namespace {

// ---- case 3: hotspot search (paper 000 §5.1.3, Fig. 3) ------------------------------------------

Co<Reading> sense_at(Ctx& t, Vec3 p, std::string sensor) {
  t.fly_to(p);
  co_return co_await t.sense(sensor);
}

Co<void> hotspot_main(Ctx& c) {
  const auto& w = dynamic_cast<const HotspotWorld&>(c.world());
  const Kind corner{"hotspot-corner"};
  Vec3 at = w.start();
  for (int i = 0; i < w.steps; ++i) {
    const double h = w.side_m / 2;
    std::vector<fleet::TaskHandle<Reading>> hs;
    for (const auto& [dx, dy] :
         std::array<std::array<double, 2>, 4>{{{-h, -h}, {h, -h}, {h, h}, {-h, h}}})
      hs.push_back(
          c.spawn(corner, {}, sense_at, Vec3{at.x + dx, at.y + dy, 0}, std::string("signal")));
    const std::vector<Reading> rs = co_await fleet::all(hs);
    const auto best = std::max_element(
        rs.begin(), rs.end(),
        [](const Reading& a, const Reading& b) { return a.values.at(0) < b.values.at(0); });
    const double dx = best->at.x - at.x, dy = best->at.y - at.y, n = std::hypot(dx, dy);
    if (n > 0) at = {at.x + w.step_m * dx / n, at.y + w.step_m * dy / n, 0};
  }
  c.metric("final_distance_to_source_m", std::hypot(at.x - w.source_m.x, at.y - w.source_m.y));
  c.metric("start_distance_to_source_m",
           std::hypot(w.start().x - w.source_m.x, w.start().y - w.source_m.y));
}

// ---- case 1: road tracing (paper 000 §5.1.1, Fig. 1) --------------------------------------------

Co<void> road_main(Ctx& c) {
  const auto& w = dynamic_cast<const RoadWorld&>(c.world());
  const Kind step{"road-step"};
  // The first point: the road's start (the user knows where the road begins).
  Vec3 p{w.road_m.front()[0], w.road_m.front()[1], 0};
  double worst = 0, sum = 0;
  for (int i = 0; i < w.steps; ++i) {
    auto h = c.spawn(step, {}, sense_at, p, std::string("road_camera"));
    const Reading r = co_await h;
    const double heading = (90.0 - r.values.at(2)) * std::numbers::pi / 180.0;  // from +x, ccw
    const auto truth = w.nearest(r.values[0], r.values[1]);
    const double off = std::hypot(r.values[0] - truth[0], r.values[1] - truth[1]);
    worst = std::max(worst, off);
    sum += std::hypot(p.x - w.nearest(p.x, p.y)[0], p.y - w.nearest(p.x, p.y)[1]);
    p = {r.values[0] + w.step_m * std::cos(heading), r.values[1] + w.step_m * std::sin(heading), 0};
  }
  c.metric("mean_offset_from_road_m", sum / w.steps);
  c.metric("steps", w.steps);
}

// ---- case 4: multiplexing (paper 000 §5.2.1, Fig. 6) --------------------------------------------

Co<void> delivery(Ctx& t, Vec3 from, Vec3 to, double handling_s) {
  t.fly_to(from);
  t.custom("pick_up", handling_s);
  t.fly_to(to);
  co_await t.custom("drop", handling_s);
}

Co<void> photo(Ctx& t, Vec3 at) {
  t.fly_to(at);
  co_await t.sense("camera");
}

Co<void> video(Ctx& t, Vec3 from, Vec3 to) {
  t.fly_to(from);
  t.custom("video_start", 1.0);
  t.fly_to(to);
  co_await t.custom("video_stop", 1.0);
}

Co<void> multiplexing_main(Ctx& c) {
  const auto& w = dynamic_cast<const SitesWorld&>(c.world());
  auto d = c.spawn(Kind{"delivery"},
                   Flags{.same_drone = true, .interruptible = w.delivery_interruptible}, delivery,
                   w.site("A"), w.site("F"), w.handling_s);
  auto b = c.spawn(Kind{"photo"}, {}, photo, w.site("B"));
  auto e = c.spawn(Kind{"photo"}, {}, photo, w.site("E"));
  auto v = c.spawn(Kind{"video"}, Flags{.same_drone = true, .interruptible = false}, video,
                   w.site("C"), w.site("D"));
  co_await d;
  co_await b;
  co_await e;
  co_await v;
}

// ---- case 2: wifi map with Gaussian-process cancellation (paper 000 §5.1.2, Fig. 8) -------------

struct WifiMap {
  explicit WifiMap(const RfFieldWorld& w) : gp(w.gp_length_m, w.gp_sigma_f, w.gp_sigma_n_db) {}
  GaussianProcess gp;
  std::vector<Vec3> cells;
  std::vector<fleet::TaskHandle<void>> tasks;
  std::vector<char> open;  // neither sensed nor cancelled
};

Co<void> wifi_cell(Ctx& t, std::size_t i, std::shared_ptr<WifiMap> map, double below_db) {
  t.fly_to(map->cells[i]);
  const Reading r = co_await t.sense("rssi");
  map->open[i] = 0;
  map->gp.add(r.at.x, r.at.y, r.values.at(0));
  // Cells the map now knows well enough are not worth a flight: cancel them.
  for (std::size_t j = 0; j < map->cells.size(); ++j)
    if (map->open[j] && map->gp.predict(map->cells[j].x, map->cells[j].y)[1] < below_db) {
      map->open[j] = 0;
      t.cancel(map->tasks[j]);
    }
}

Co<void> wifi_main(Ctx& c) {
  const auto& w = dynamic_cast<const RfFieldWorld&>(c.world());
  auto map = std::make_shared<WifiMap>(w);
  double x0 = 1e18, y0 = 1e18;
  for (const auto& p : w.fence()) x0 = std::min(x0, p[0]), y0 = std::min(y0, p[1]);
  const int nx = std::max(1, static_cast<int>(std::floor(w.width_m / w.cell_m + 1e-9)));
  const int ny = std::max(1, static_cast<int>(std::floor(w.height_m / w.cell_m + 1e-9)));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      map->cells.push_back({x0 + (i + 0.5) * w.cell_m, y0 + (j + 0.5) * w.cell_m, 0});
  map->open.assign(map->cells.size(), 1);
  const Kind cell{"wifi-cell"};
  for (std::size_t i = 0; i < map->cells.size(); ++i)
    map->tasks.push_back(c.spawn(cell, {}, wifi_cell, i, map, w.cancel_below_db));
  int cancelled = 0;
  for (auto& h : map->tasks) {
    try {
      co_await h;
    } catch (const fleet::TaskCancelled&) {
      ++cancelled;
    }
  }
  double se = 0;
  for (const Vec3& p : map->cells) {
    const double e = map->gp.predict(p.x, p.y)[0] - w.truth_dbm(p.x, p.y);
    se += e * e;
  }
  c.metric("cells", static_cast<double>(map->cells.size()));
  c.metric("cells_cancelled", cancelled);
  c.metric("map_rmse_db", std::sqrt(se / static_cast<double>(map->cells.size())));
}

// ---- case 5: tracking with hand-off (paper 000 §5.2.2, Fig. 6) ----------------------------------

Co<void> tracking_main(Ctx& c) {
  const auto& w = dynamic_cast<const TrackingWorld&>(c.world());
  const Kind look{"tracking-look"};
  // Where to look: the last sighting moved on at the walker's estimated velocity (from the last
  // two sightings), a couple of seconds ahead for the flight there.
  Vec3 last = w.start();
  double vx = 0, vy = 0, t_last = 0, seen_s = 0, longest_gap = 0;
  int looks = 0, hits = 0, handoffs = 0, last_drone = -1;
  while (c.now_s() < w.duration_s) {
    const double ahead = std::min(c.now_s() - t_last + 2.0, 10.0);  // beyond: a guess
    const Vec3 target{last.x + vx * ahead, last.y + vy * ahead, 0};
    const double asked_s = c.now_s();
    auto h = c.spawn(look, {}, sense_at, target, std::string("camera"));
    Reading r;
    try {
      r = co_await h;
    } catch (const fleet::ActionFailed&) {
      // A look lost on the way: look again. One refused at once (the walker left the fence):
      // the same look would be refused again at the same instant, forever; stop following.
      if (c.now_s() == asked_s) break;
      continue;
    }
    ++looks;
    if (last_drone >= 0 && r.drone != last_drone) ++handoffs;
    last_drone = r.drone;
    if (r.values.size() == 2) {
      ++hits;
      if (looks > 1 && r.t_s > t_last) {
        vx = (r.values[0] - last.x) / (r.t_s - t_last);
        vy = (r.values[1] - last.y) / (r.t_s - t_last);
        const double v = std::hypot(vx, vy), cap = w.walker_speed_m_s;
        if (v > cap) vx *= cap / v, vy *= cap / v;
      }
      longest_gap = std::max(longest_gap, r.t_s - seen_s);
      seen_s = t_last = r.t_s;
      last = {r.values[0], r.values[1], 0};
    }
  }
  longest_gap = std::max(longest_gap, c.now_s() - seen_s);
  c.metric("looks", looks);
  c.metric("tracked_share", looks > 0 ? static_cast<double>(hits) / looks : 0.0);
  c.metric("longest_gap_s", longest_gap);
  c.metric("handoffs", handoffs);
}

// ---- static: tasks from a file (docs/swath-fleet.md)
// ---------------------------------------------

struct StaticRun {
  std::vector<fleet::TaskHandle<void>> handles;
};

Co<void> static_task(Ctx& t, const StaticWorld::Task* task, std::shared_ptr<StaticRun> run) {
  for (std::size_t a : task->after) co_await run->handles[a];
  fleet::Future<Reading> last;
  for (const auto& s : task->steps) {
    switch (s.type) {
      case 0:
        last = t.fly_to(s.to);
        break;
      case 1:
        last = t.sense(s.name);
        break;
      case 2:
        last = t.hover(s.seconds);
        break;
      default:
        last = t.custom(s.name, s.seconds);
        break;
    }
  }
  co_await last;
}

Co<void> static_main(Ctx& c) {
  const auto& w = dynamic_cast<const StaticWorld&>(c.world());
  auto run = std::make_shared<StaticRun>();
  run->handles.resize(w.tasks.size());
  // Spawned in an order where every task's predecessors exist first (the file has no cycle).
  std::vector<char> spawned(w.tasks.size(), 0);
  for (std::size_t done = 0; done < w.tasks.size();) {
    for (std::size_t i = 0; i < w.tasks.size(); ++i) {
      if (spawned[i]) continue;
      if (std::any_of(w.tasks[i].after.begin(), w.tasks[i].after.end(),
                      [&](std::size_t a) { return !spawned[a]; }))
        continue;
      run->handles[i] =
          c.spawn(Kind{w.tasks[i].kind}, w.tasks[i].flags, static_task, &w.tasks[i], run);
      spawned[i] = 1;
      ++done;
    }
  }
  int failed = 0;
  for (auto& h : run->handles) {
    try {
      co_await h;
    } catch (const fleet::ActionFailed&) {
      ++failed;
    } catch (const fleet::TaskCancelled&) {
      ++failed;
    }
  }
  c.metric("tasks", static_cast<double>(w.tasks.size()));
  c.metric("tasks_failed", failed);
}

}  // namespace

namespace {

struct Registered {
  fleet::App app;
  std::string world_kind;
};
std::vector<Registered>& registered() {
  static std::vector<Registered> apps;
  return apps;
}

}  // namespace

void register_app(fleet::App app, const std::string& world_kind, bool replace) {
  const std::vector<std::string>& kinds = worlds::world_kinds();
  if (app.name.empty()) throw std::invalid_argument("register_app: an app needs a name");
  if (std::find(kinds.begin(), kinds.end(), world_kind) == kinds.end())
    throw std::invalid_argument("register_app: " + app.name + ": unknown world kind \"" +
                                world_kind + "\"");
  for (const fleet::App& a : replace ? std::vector<fleet::App>{} : all_apps())
    if (a.name == app.name)
      throw std::invalid_argument("register_app: the name " + app.name + " is taken");
  if (!app.main) throw std::invalid_argument("register_app: " + app.name + " has no main");
  registered().push_back({std::move(app), world_kind});
}

std::vector<fleet::App> all_apps() {
  std::vector<fleet::App> out = builtin_apps();
  for (const Registered& r : registered()) {
    // One that replaces a built-in app takes its place.
    const auto same = std::find_if(out.begin(), out.end(),
                                   [&](const fleet::App& a) { return a.name == r.app.name; });
    if (same != out.end())
      *same = r.app;
    else
      out.push_back(r.app);
  }
  return out;
}

std::string app_world_kind(const std::string& app) {
  for (const Registered& r : registered())
    if (r.app.name == app) return r.world_kind;
  if (app == "multiplexing") return "sites";
  if (app == "wifi") return "rf_field";
  return app;
}

std::vector<fleet::App> builtin_apps() {
  return {
      {"hotspot", "case 3 (paper 000 §5.1.3): find a signal source by sensing square corners",
       hotspot_main},
      {"multiplexing",
       "case 4 (paper 000 §5.2.1): a delivery, two photos and a video sharing one drone (world "
       "kind sites)",
       multiplexing_main},
      {"road", "case 1 (paper 000 §5.1.1): trace a road step by step with a road camera",
       road_main},
      {"static",
       "tasks from a world file (kind static): fly, sense, hover, custom, in order after their "
       "predecessors",
       static_main},
      {"tracking",
       "case 5 (paper 000 §5.2.2): follow a walker, handing over between short-flight drones",
       tracking_main},
      {"wifi",
       "case 2 (paper 000 §5.1.2): map a Wi-Fi field cell by cell, cancelling cells a Gaussian "
       "process "
       "already knows (world kind rf_field)",
       wifi_main},
  };
}

double multiplexing_optimum_s(const worlds::SitesWorld& w, const Vec3& home, const Kinematics& k,
                              double altitude_m) {
  // Segments: place and service. Order constraints by index: 0 A, 1 F, 2 B, 3 E, 4 C, 5 D.
  const std::array<std::string, 6> names{"A", "F", "B", "E", "C", "D"};
  const double camera = w.sense_time_s("camera");
  const std::array<double, 6> service{w.handling_s, w.handling_s, camera, camera, 1.0, 1.0};
  std::array<int, 6> order{0, 1, 2, 3, 4, 5};
  double best = std::numeric_limits<double>::infinity();
  do {
    std::array<int, 6> pos{};
    for (int i = 0; i < 6; ++i)
      pos[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])] = i;
    if (pos[0] > pos[1] || pos[5] != pos[4] + 1) continue;
    if (!w.delivery_interruptible && pos[1] != pos[0] + 1) continue;
    double t = altitude_m / k.climb_m_s;
    Vec3 at = home;
    for (int i : order) {
      const Vec3 p = w.site(names[static_cast<std::size_t>(i)]);
      t += fleet::rest_to_rest_s(std::hypot(p.x - at.x, p.y - at.y), k.cruise_m_s, k.approach_m_s,
                                 k.approach_within_m, k.accel_m_s2) +
           service[static_cast<std::size_t>(i)];
      at = p;
    }
    best = std::min(best, t);
  } while (std::next_permutation(order.begin(), order.end()));
  return best;
}

}  // namespace swath::fleet
