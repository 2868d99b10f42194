#include "energy_images.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "swath/base/number_text.hpp"
#include "swath/energy/flight.hpp"
#include "swath/render/legend.hpp"

namespace swath::apps {
namespace {

using geometry::Point2;
using render::Color;

const Color kInk{0.1f, 0.1f, 0.1f, 1};
const Color kPlanned{0.62f, 0.62f, 0.62f, 1};

}  // namespace

Color soc_color(double soc, const energy::Battery& battery) {
  const double span = battery.initial_soc - battery.reserve_soc;
  const auto t = static_cast<float>(std::clamp((soc - battery.reserve_soc) / span, 0.0, 1.0));
  return {0.85f * (1 - t) + 0.1f * t, 0.15f * (1 - t) + 0.65f * t, 0.1f, 1};
}

TrajectoryImage trajectory_image(const energy::SimulationResult& r, const energy::SimConfig& config,
                                 int width_px, int height_px) {
  TrajectoryImage out;
  render::Scene& scene = out.scene;
  MapBounds bounds;
  auto grow = [&](Point2 p) { bounds.add(p); };
  for (Point2 p : r.planned_path) grow(p);
  for (const auto& s : r.samples) grow(s.position);
  for (Point2 p : r.planned_triggers) grow(p);
  grow(config.start);
  const int text_h = std::max(12, height_px / 50);
  const int top = 2 * (text_h + 6) + 16;
  out.view = render::fit(bounds.lo, bounds.hi, width_px, height_px - top + 40, 40);
  out.view.origin_y_m += top / out.view.px_per_m / 2;  // room for the title
  out.view.height_px = height_px;

  scene.polylines.push_back({r.planned_path, 2.0, kPlanned});
  // The flight in pieces of about one colour.
  const std::size_t piece = std::max<std::size_t>(2, r.samples.size() / 200);
  for (std::size_t i = 0; i + 1 < r.samples.size(); i += piece) {
    render::Polyline line;
    line.width_px = 3.0;
    for (std::size_t k = i; k <= std::min(i + piece, r.samples.size() - 1); ++k)
      line.points.push_back(r.samples[k].position);
    line.color = soc_color(r.samples[i].soc, config.battery);
    scene.polylines.push_back(std::move(line));
  }
  for (Point2 p : r.planned_triggers)
    scene.markers.push_back({p, 12.0, kInk, render::MarkerShape::triangle});
  scene.markers.push_back({config.start, 10.0, kInk, render::MarkerShape::square});

  using base::fixed_text;
  std::string title = "swath-energy: ";
  title += energy::to_string(r.status);
  title += " in " + fixed_text(r.flight_time_s, 0) + " s, " + fixed_text(r.energy_j / 3600, 2) +
           " Wh, SoC " + fixed_text(100 * r.final_soc, 1) + " %";
  scene.labels.push_back(
      {10, text_h + 8, title, render::fitted_text_height(title, width_px - 60.0, text_h), kInk});
  const std::string key =
      "grey: plan; flight coloured by state of charge (green full, red at the reserve); "
      "triangles: triggering points";
  scene.labels.push_back({10, 2 * (text_h + 6) + 8, key,
                          render::fitted_text_height(key, width_px - 60.0, 0.8 * text_h), kInk});
  out.scale_bar = add_scale_bar(scene, out.view, width_px, height_px, text_h);
  add_north_arrow(scene, width_px, top + 20.0, text_h);
  if (config.wind.speed_m_s() > 0) {
    // An arrow the way the air moves, bottom right.
    const Point2 w = config.wind.velocity_m_s();
    const double n = std::hypot(w.x, w.y);
    const Point2 dir{w.x / n, -w.y / n};  // pixels: y down
    const Point2 c{width_px - 50.0, height_px - 50.0};
    const Point2 a{c.x - 20 * dir.x, c.y - 20 * dir.y}, b{c.x + 20 * dir.x, c.y + 20 * dir.y};
    scene.screen_polylines.push_back({{a, b}, 3, kInk});
    const Point2 side{-dir.y, dir.x};
    scene.screen_polygons.push_back({{{{b.x + 8 * dir.x, b.y + 8 * dir.y},
                                       {b.x + 6 * side.x, b.y + 6 * side.y},
                                       {b.x - 6 * side.x, b.y - 6 * side.y}}},
                                     kInk});
    scene.labels.push_back({static_cast<int>(c.x) - 40, static_cast<int>(c.y) - 30,
                            "wind " + fixed_text(config.wind.speed_m_s(), 1) + " m/s", 0.8 * text_h,
                            kInk});
  }
  return out;
}

EnergyImage energy_image(const energy::SimulationResult& r, const energy::Plan& plan,
                         const energy::SimConfig& config, int width_px, int height_px) {
  EnergyImage out;
  out.view = render::View{1.0, 0.0, 0.0, width_px, height_px};
  const int panel = height_px / 3;
  std::vector<double> t, measured, model, soc;
  for (const auto& s : r.samples) {
    t.push_back(s.t_s);
    measured.push_back(std::isfinite(s.measured_w) ? s.measured_w : s.model_w);
    model.push_back(s.model_w);
    soc.push_back(100 * s.soc);
  }
  const double t_end = t.empty() ? 1.0 : t.back();
  std::vector<render::ChartSpec> specs(3);
  specs[0] = {"Power",
              "time (s)",
              "W",
              {{"measured", t, measured, {0.6f, 0.6f, 0.6f, 1}, 1.0},
               {"model", t, model, {0.1f, 0.3f, 0.85f, 1}, 2.0}}};
  const double reserve = 100 * config.battery.reserve_soc;
  specs[1] = {"State of charge",
              "time (s)",
              "%",
              {{"SoC", t, soc, {0.1f, 0.6f, 0.2f, 1}, 2.0},
               {"reserve", {0.0, t_end}, {reserve, reserve}, {0.85f, 0.15f, 0.1f, 1}, 1.5}}};
  // Parameters as steps, each as its level within the widest of its stages' bounds ([0, 0], a
  // computation switched off, does not count: a plan may start with it off).
  auto widest = [&plan](auto bounds_of) {
    energy::Interval w{INFINITY, -INFINITY};
    for (const energy::Stage& stage : plan.stages) {
      const energy::Interval b = bounds_of(stage);
      if (b.lo == 0 && b.hi == 0) continue;
      w = {std::min(w.lo, b.lo), std::max(w.hi, b.hi)};
    }
    return w.lo <= w.hi ? w : energy::Interval{0, 0};
  };
  const energy::Stage& first = plan.stages.front();
  std::vector<render::Series> levels;
  const Color palette[] = {{0.55f, 0.1f, 0.75f, 1},
                           {0.95f, 0.55f, 0.0f, 1},
                           {0.0f, 0.55f, 0.55f, 1},
                           {0.5f, 0.35f, 0.1f, 1}};
  auto add_steps = [&](const std::string& name, const energy::Interval& b, auto value_of) {
    render::Series s{name, {}, {}, palette[levels.size() % 4], 2.0};
    const double span = b.hi - b.lo;
    for (std::size_t i = 0; i < r.control.size(); ++i) {
      const double level = span > 0 ? (value_of(r.control[i]) - b.lo) / span : 1.0;
      if (i > 0) {
        s.x.push_back(r.control[i].t_s);
        s.y.push_back(s.y.back());
      }
      s.x.push_back(r.control[i].t_s);
      s.y.push_back(level);
    }
    s.x.push_back(t_end);
    s.y.push_back(s.y.back());
    levels.push_back(std::move(s));
  };
  for (std::size_t i = 0; i < first.trajectory.size(); ++i) {
    std::string name = "c";
    name += std::to_string(i + 1);
    add_steps(name, widest([i](const energy::Stage& st) { return st.trajectory[i]; }),
              [i](const energy::ControlSample& c) { return c.trajectory[i]; });
  }
  for (std::size_t j = 0; j < first.computations.size(); ++j) {
    std::string name = "s";
    name += std::to_string(j + 1);
    if (j < config.power.computations.size()) name = config.power.computations[j].name;
    add_steps(name, widest([j](const energy::Stage& st) { return st.computations[j]; }),
              [j](const energy::ControlSample& c) { return c.computations[j]; });
  }
  specs[2] = {"Parameters (0 lowest, 1 highest)", "time (s)", "level", levels};
  for (int k = 0; k < 3; ++k) {
    if (specs[k].series.empty() || specs[k].series.front().x.empty()) continue;
    render::ChartLayout layout{};
    const render::Scene part = render::chart_scene(specs[k], width_px, panel, &layout);
    render::stack_scene(out.scene, part, k * panel);
    out.charts.push_back(layout);
    out.offsets_px.push_back(k * panel);
  }
  return out;
}

}  // namespace swath::apps
