#include "control_images.hpp"

#include <algorithm>
#include <cmath>

#include "map_furniture.hpp"
#include "swath/base/number_text.hpp"
#include "swath/render/legend.hpp"

namespace swath::apps {
namespace {

using base::fixed_text;
using geometry::Point2;
using render::Color;

const Color kInk{0.1f, 0.1f, 0.1f, 1};
const Color kPlanned{0.62f, 0.62f, 0.62f, 1};
const Color kArea{0.86f, 0.93f, 0.84f, 1};
const Color kAreaOutline{0.35f, 0.55f, 0.3f, 1};
const Color kNoFly{0.95f, 0.72f, 0.72f, 1};
const Color kNoFlyOutline{0.75f, 0.1f, 0.1f, 1};
const Color kBlue{0.1f, 0.3f, 0.85f, 1};
const Color kOrange{0.95f, 0.55f, 0.0f, 1};
const Color kGreen{0.1f, 0.6f, 0.2f, 1};
const Color kRed{0.85f, 0.15f, 0.1f, 1};
const Color kGrey{0.6f, 0.6f, 0.6f, 1};

// Green at 0 through yellow to red at `worst`.
Color error_color(double e, double worst) {
  const auto t = static_cast<float>(std::clamp(e / worst, 0.0, 1.0));
  return t < 0.5f ? Color{0.1f + 1.6f * t, 0.65f, 0.1f, 1}
                  : Color{0.9f, 0.65f - 1.0f * (t - 0.5f), 0.1f, 1};
}

std::vector<Point2> flat(const std::vector<control::Vec3>& points) {
  std::vector<Point2> out;
  for (const auto& p : points) out.push_back({p.x, p.y});
  return out;
}

ControlPicture stacked(std::vector<render::ChartSpec> specs, int width_px, int height_px) {
  ControlPicture out;
  out.view = render::View{1.0, 0.0, 0.0, width_px, height_px};
  const int panel = height_px / static_cast<int>(specs.size());
  for (std::size_t k = 0; k < specs.size(); ++k) {
    if (specs[k].series.empty() || specs[k].series.front().x.empty()) {
      // A flight that ended before its first logged row (a --max-time below the log's 20 ms):
      // the panel says so rather than staying blank.
      const double text_h = std::max(11.0, panel / 20.0);
      const int y = static_cast<int>(static_cast<double>(k) * panel);
      out.scene.labels.push_back({static_cast<int>(text_h), y + static_cast<int>(1.5 * text_h),
                                  specs[k].title, text_h, kInk});
      out.scene.labels.push_back({static_cast<int>(text_h), y + static_cast<int>(3.5 * text_h),
                                  "no samples: the flight ended before its first logged row",
                                  text_h, kGrey});
      continue;
    }
    render::ChartLayout layout{};
    const render::Scene part = render::chart_scene(specs[k], width_px, panel, &layout);
    const double dy = static_cast<double>(k) * panel;
    render::stack_scene(out.scene, part, dy);
    out.charts.push_back(layout);
    out.offsets_px.push_back(dy);
  }
  return out;
}

template <typename F>
render::Series series(const FlightSeries& flight, std::string name, Color color, double width,
                      F value) {
  render::Series s{std::move(name), {}, {}, color, width};
  for (const auto& r : flight.rows()) {
    s.x.push_back(r.t_s);
    s.y.push_back(value(r));
  }
  return s;
}

}  // namespace

void FlightSeries::add(const control::TimeseriesRow& row) {
  if (seen_++ % stride_ != 0) return;
  rows_.push_back(row);
  if (rows_.size() < kMaxKept) return;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < rows_.size(); i += 2) rows_[kept++] = rows_[i];
  rows_.resize(kept);
  stride_ *= 2;
}

ControlPicture trajectory_picture(const control::SimulationSettings& settings,
                                  const control::SimulationSummary& summary,
                                  const FlightSeries& flight, int width_px, int height_px) {
  ControlPicture out;
  render::Scene& scene = out.scene;
  const control::FlightMission& mission = settings.mission;
  MapBounds bounds;
  for (const auto& leg : mission.legs)
    for (const auto& p : leg) bounds.add({p.x, p.y});
  for (const auto& r : flight.rows()) bounds.add({r.position_m.x, r.position_m.y});
  for (const auto& ring : mission.area)
    for (Point2 p : ring) bounds.add(p);
  for (const auto& ring : mission.no_fly)
    for (Point2 p : ring) bounds.add(p);
  const int text_h = std::max(12, height_px / 50);
  const int top = 2 * (text_h + 6) + 16;
  const render::PixelBox map_box{40.0, static_cast<double>(top), width_px - 40.0, height_px - 60.0};
  out.view = render::fit_into(bounds.lo, bounds.hi, map_box, width_px, height_px);

  if (!mission.area.empty()) scene.polygons.push_back({mission.area, kArea, kAreaOutline, 1.5});
  for (const auto& zone : mission.no_fly)
    scene.polygons.push_back({{zone}, kNoFly, kNoFlyOutline, 2.0});
  for (const auto& leg : mission.legs) scene.polylines.push_back({flat(leg), 2.0, kPlanned});
  // The flight in pieces of about one colour.
  const auto& rows = flight.rows();
  double worst = 1.0;
  for (const auto& r : rows) worst = std::max(worst, r.cross_track_m);
  const std::size_t piece = std::max<std::size_t>(2, rows.size() / 300);
  for (std::size_t i = 0; i + 1 < rows.size(); i += piece) {
    render::Polyline line;
    line.width_px = 3.0;
    double e = 0;
    for (std::size_t k = i; k <= std::min(i + piece, rows.size() - 1); ++k) {
      line.points.push_back({rows[k].position_m.x, rows[k].position_m.y});
      e = std::max(e, rows[k].cross_track_m);
    }
    line.color = error_color(e, worst);
    scene.polylines.push_back(std::move(line));
  }
  const auto& first = mission.legs.front().front();
  scene.markers.push_back({{first.x, first.y}, 12.0, kInk, render::MarkerShape::square});
  if (!rows.empty())
    scene.markers.push_back({{rows.back().position_m.x, rows.back().position_m.y},
                             11.0,
                             kInk,
                             render::MarkerShape::disc});

  std::string title = "swath-control: " + std::string(control::to_string(summary.status)) +
                      " after " + fixed_text(summary.flight_time_s, 0) + " s; cross-track RMS " +
                      fixed_text(summary.cross_track_m.rms, 2) + " m, max " +
                      fixed_text(summary.cross_track_m.max, 2) + " m";
  if (summary.min_clearance_m)
    title += "; least clearance " + fixed_text(*summary.min_clearance_m, 2) + " m";
  scene.labels.push_back(
      {10, text_h + 8, title, render::fitted_text_height(title, width_px - 60.0, text_h), kInk});
  const std::string sub = settings.mission.name + ", " + settings.physics.airframe.name + ", " +
                          settings.environment.name + " wind, seed " +
                          std::to_string(settings.seed);
  scene.labels.push_back({10, 2 * (text_h + 6) + 8, sub,
                          render::fitted_text_height(sub, width_px - 60.0, 0.8 * text_h), kInk});
  std::vector<render::LegendEntry> legend{
      {"mission", render::SwatchKind::line, kPlanned},
      {"flight, cross-track 0 m", render::SwatchKind::line, error_color(0, 1)},
      {"cross-track " + fixed_text(worst, 1) + " m", render::SwatchKind::line, error_color(1, 1)},
      {"start", render::SwatchKind::marker, kInk, {0, 0, 0, 0}, render::MarkerShape::square},
      {"end", render::SwatchKind::marker, kInk, {0, 0, 0, 0}, render::MarkerShape::disc}};
  if (!mission.area.empty())
    legend.push_back({"area", render::SwatchKind::fill, kArea, kAreaOutline});
  if (!mission.no_fly.empty())
    legend.push_back({"no-fly zone", render::SwatchKind::fill, kNoFly, kNoFlyOutline});
  render::add_legend(scene, legend, map_box, render::Corner::bottom_right, 0.8 * text_h);
  add_scale_bar(scene, out.view, width_px, height_px, text_h);
  add_north_arrow(scene, width_px, top + 20.0, text_h);
  return out;
}

ControlPicture attitude_picture(const FlightSeries& flight, int width_px, int height_px) {
  using R = control::TimeseriesRow;
  std::vector<render::ChartSpec> specs(3);
  specs[0] = {"Roll (right wing down)",
              "time (s)",
              "deg",
              {series(flight, "setpoint", kGrey, 1.5, [](const R& r) { return r.setpoint_deg.x; }),
               series(flight, "true", kBlue, 1.5, [](const R& r) { return r.attitude_deg.x; })}};
  specs[1] = {"Pitch (nose up)",
              "time (s)",
              "deg",
              {series(flight, "setpoint", kGrey, 1.5, [](const R& r) { return r.setpoint_deg.y; }),
               series(flight, "true", kBlue, 1.5, [](const R& r) { return r.attitude_deg.y; })}};
  specs[2] = {
      "Tracking", "time (s)", "m", {series(flight, "cross-track", kOrange, 1.5, [](const R& r) {
        return r.cross_track_m;
      })}};
  return stacked(std::move(specs), width_px, height_px);
}

ControlPicture energy_picture(const control::SimulationSettings& settings,
                              const FlightSeries& flight, int width_px, int height_px) {
  using R = control::TimeseriesRow;
  std::vector<render::ChartSpec> specs(3);
  specs[0] = {
      "Power",
      "time (s)",
      "W",
      {series(flight, "motors", kBlue, 1.5, [](const R& r) { return r.motors_w; }),
       series(flight, "avionics", kGreen, 1.5, [](const R& r) { return r.avionics_w; }),
       series(flight, "flight computer", kOrange, 1.5, [](const R& r) { return r.cpu_w; })}};
  const double reserve = 100 * settings.battery.reserve_soc;
  const double t_end = flight.rows().empty() ? 1.0 : flight.rows().back().t_s;
  specs[1] = {"State of charge",
              "time (s)",
              "%",
              {series(flight, "SoC", kGreen, 2.0, [](const R& r) { return 100 * r.soc; }),
               {"reserve", {0.0, t_end}, {reserve, reserve}, kRed, 1.5}}};
  specs[2] = {"Control executions",
              "time (s)",
              "1/s",
              {series(flight, "executions in the last second", kBlue, 1.5,
                      [](const R& r) { return static_cast<double>(r.executions_last_s); })}};
  return stacked(std::move(specs), width_px, height_px);
}

namespace {

const Color kModeColors[] = {{0.1f, 0.3f, 0.85f, 1},  {0.95f, 0.55f, 0.0f, 1},
                             {0.1f, 0.6f, 0.2f, 1},   {0.55f, 0.1f, 0.75f, 1},
                             {0.85f, 0.15f, 0.1f, 1}, {0.0f, 0.55f, 0.55f, 1}};

std::string group_key(const std::vector<ComparedGroup>& groups) {
  std::string key;
  for (std::size_t g = 0; g < groups.size(); ++g)
    key += (g ? ", " : "") + std::to_string(g + 1) + " " + groups[g].label;
  return key;
}

// A mode's means through the groups (named, for the legend) and its intervals as bars.
void add_intervals(std::vector<render::Series>& series, const std::vector<ComparedGroup>& groups,
                   std::size_t mode, const std::string& name,
                   std::vector<control::MeanInterval> ComparedGroup::*metric) {
  const Color color = kModeColors[mode % 6];
  render::Series means{name, {}, {}, color, 2.0};
  const double offset = 0.06 * static_cast<double>(mode);  // bars side by side
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const control::MeanInterval& m = (groups[g].*metric)[mode];
    const double x = static_cast<double>(g + 1) + offset;
    means.x.push_back(x);
    means.y.push_back(100 * m.mean);
    series.push_back({"", {x, x}, {100 * m.low, 100 * m.high}, color, 3.0});
  }
  series.push_back(std::move(means));
}

}  // namespace

ControlPicture improvement_picture(const std::vector<ComparedGroup>& groups,
                                   const std::vector<std::string>& modes, int width_px,
                                   int height_px) {
  std::vector<render::ChartSpec> specs{
      {"Attitude RMS improvement over " + modes.front() + " (%, + = smaller error)",
       "groups: " + group_key(groups),
       "%",
       {}},
      {"Cross-track RMS improvement (%)", "groups: " + group_key(groups), "%", {}},
      {"Flight time (%, + = longer)", "groups: " + group_key(groups), "%", {}}};
  for (std::size_t m = 1; m < modes.size(); ++m) {
    add_intervals(specs[0].series, groups, m - 1, modes[m], &ComparedGroup::attitude);
    add_intervals(specs[1].series, groups, m - 1, modes[m], &ComparedGroup::cross_track);
    add_intervals(specs[2].series, groups, m - 1, modes[m], &ComparedGroup::flight_time);
  }
  return stacked(std::move(specs), width_px, height_px);
}

ControlPicture rate_picture(const std::vector<ComparedGroup>& groups,
                            const std::vector<std::string>& modes, int width_px, int height_px) {
  render::ChartSpec spec{
      "Control executions per second", "groups: " + group_key(groups), "1/s", {}};
  for (std::size_t m = 0; m < modes.size(); ++m) {
    render::Series s{modes[m], {}, {}, m == 0 ? kInk : kModeColors[(m - 1) % 6], 2.0};
    for (std::size_t g = 0; g < groups.size(); ++g) {
      s.x.push_back(static_cast<double>(g + 1));
      s.y.push_back(groups[g].executions_per_s[m]);
    }
    spec.series.push_back(std::move(s));
  }
  return stacked({spec}, width_px, height_px);
}

ControlPicture sweep_picture(const std::vector<SweptCurve>& curves, const std::string& title,
                             const std::string& x_label, const std::string& y_label, int width_px,
                             int height_px) {
  render::ChartSpec spec{title, x_label, y_label, {}};
  // Bars of neighbouring curves side by side, a small fraction of the values' spacing apart.
  double spacing = 1;
  for (const SweptCurve& c : curves)
    for (std::size_t k = 1; k < c.x.size(); ++k)
      if (c.x[k] != c.x[k - 1]) spacing = std::min(spacing, std::abs(c.x[k] - c.x[k - 1]));
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const Color color = kModeColors[c % 6];
    render::Series means{curves[c].label, {}, {}, color, 2.0};
    const double offset = 0.04 * spacing * static_cast<double>(c);
    for (std::size_t k = 0; k < curves[c].x.size() && k < curves[c].y.size(); ++k) {
      const double x = curves[c].x[k] + offset;
      const control::MeanInterval& m = curves[c].y[k];
      means.x.push_back(x);
      means.y.push_back(m.mean);
      spec.series.push_back({"", {x, x}, {m.low, m.high}, color, 3.0});
    }
    spec.series.push_back(std::move(means));
  }
  return stacked({spec}, width_px, height_px);
}

ControlPicture triggers_picture(const std::vector<control::RateRow>& rates, const Raster& raster,
                                const std::vector<std::string>& trigger_sensors, int width_px,
                                int height_px) {
  static constexpr const char* kCauses[] = {"time-triggered", "boot", "trigger", "failsafe",
                                            "setpoint"};
  const Color palette[] = {kGrey, kGreen, kBlue, kRed, kOrange};
  // 1. Executions per second, in all and by cause.
  std::vector<render::Series> series;
  render::Series all{"all", {}, {}, kInk, 2.0};
  for (const auto& r : rates) {
    all.x.push_back(r.second);
    all.y.push_back(r.executions);
  }
  series.push_back(all);
  for (std::size_t c = 0; c < 5; ++c) {
    render::Series one{kCauses[c], {}, {}, palette[c], 1.5};
    bool any = false;
    for (const auto& r : rates) {
      one.x.push_back(r.second);
      one.y.push_back(r.by_cause[c]);
      any = any || r.by_cause[c] > 0;
    }
    if (any) series.push_back(std::move(one));
  }
  ControlPicture out =
      stacked({{"Control executions per second (paper 002 Fig. 11)", "time (s)", "1/s", series}},
              width_px, height_px / 2);
  out.view.height_px = height_px;
  // 2. The raster, below: one row per cause, one for unchanged outputs, one per sensor.
  std::vector<std::pair<std::string, std::vector<double>>> rows;
  for (std::size_t c = 0; c < 5; ++c) {
    std::vector<double> ticks;
    for (const auto& [t, cause] : raster.executions)
      if (static_cast<std::size_t>(cause) == c) ticks.push_back(t);
    if (!ticks.empty()) rows.push_back({std::string("execution: ") + kCauses[c], ticks});
  }
  rows.push_back({"output unchanged", raster.unchanged});
  for (std::size_t k = 0; k < trigger_sensors.size(); ++k)
    rows.push_back({"trigger: " + trigger_sensors[k],
                    k < raster.triggers.size() ? raster.triggers[k] : std::vector<double>{}});
  const double top = height_px / 2.0 + 40, bottom = height_px - 40.0;
  const double left = 200, right = width_px - 30.0;
  const double row_h = (bottom - top) / static_cast<double>(rows.size());
  const int text_h = std::max(10, static_cast<int>(std::min(row_h * 0.6, 16.0)));
  const std::string title = "Two seconds from " + fixed_text(raster.from_s, 1) + " s";
  out.scene.labels.push_back({static_cast<int>(left), static_cast<int>(top - 12), title,
                              static_cast<double>(text_h), kInk});
  const double span = raster.to_s - raster.from_s;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const double y0 = top + static_cast<double>(r) * row_h, y1 = y0 + row_h * 0.8;
    out.scene.labels.push_back({10, static_cast<int>(y1), rows[r].first,
                                render::fitted_text_height(rows[r].first, left - 20, text_h),
                                kInk});
    out.scene.screen_polylines.push_back({{{left, y1}, {right, y1}}, 1.0, kGrey});
    for (double t : rows[r].second) {
      const double x = left + (t - raster.from_s) / span * (right - left);
      out.scene.screen_polylines.push_back({{{x, y0}, {x, y1}}, 1.0, kBlue});
    }
  }
  return out;
}

std::vector<std::string> control_image_names() {
  return {"trajectory.png", "attitude.png", "energy.png", "triggers.png"};
}

void add_control_images(base::OutputSet& set, const control::SimulationSettings& settings,
                        const control::SimulationSummary& summary, const FlightSeries& flight,
                        const std::vector<control::RateRow>& rates, const Raster& raster,
                        int width_px, int height_px) {
  auto png = [](const ControlPicture& p) {
    return render::encode_png(render::draw(p.scene, p.view));
  };
  set.add("trajectory.png",
          png(trajectory_picture(settings, summary, flight, width_px, height_px)));
  set.add("attitude.png", png(attitude_picture(flight, width_px, height_px)));
  set.add("energy.png", png(energy_picture(settings, flight, width_px, height_px)));
  set.add("triggers.png",
          png(triggers_picture(rates, raster, control::trigger_sensor_names(settings.physics),
                               width_px, height_px)));
}

}  // namespace swath::apps
