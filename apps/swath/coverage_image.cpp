#include "coverage_image.hpp"

#include "map_furniture.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/planning/survey.hpp"
#include "swath/render/legend.hpp"

namespace swath::apps {
namespace {

using geometry::Point2;
using render::Color;

const Color kArea{0.85f, 0.93f, 0.82f, 1};
const Color kOutline{0.25f, 0.45f, 0.25f, 1};
const Color kFootprint{0.15f, 0.35f, 0.85f, 0.16f};
const Color kNoFly{0.9f, 0.2f, 0.15f, 0.35f};
const Color kNoFlyOutline{0.75f, 0.1f, 0.05f, 1};
const Color kInk{0.1f, 0.1f, 0.1f, 1};
const Color kDrone[] = {{0.85f, 0.15f, 0.1f, 1}, {0.55f, 0.1f, 0.75f, 1}, {0.95f, 0.55f, 0.0f, 1},
                        {0.0f, 0.55f, 0.55f, 1}, {0.5f, 0.35f, 0.1f, 1},  {0.9f, 0.2f, 0.6f, 1}};

Color drone_color(int drone) {
  return kDrone[(drone - 1 + 6 * 1000) % 6];
}

std::vector<Point2> local(const std::vector<geometry::GeoPoint>& points,
                          const geometry::LocalFrame& frame) {
  std::vector<Point2> out;
  for (const geometry::GeoPoint& g : points) out.push_back(frame.to_local(g));
  return out;
}

std::string drone_name(const planning::PlanFigures::Drone& d) {
  std::string name = "drone " + std::to_string(d.drone);
  if (!d.name.empty() && d.name != "drone-" + std::to_string(d.drone)) name += " " + d.name;
  return name;
}

/// Each drone's path (no arrows here: add_line_arrows), and where its lines start and end.
template <class Grow>
void add_paths(render::Scene& scene, const planning::PlanFeatures& features,
               const geometry::LocalFrame& frame, double mark, Grow& grow) {
  for (const auto& path : features.paths) {
    const std::vector<Point2> points = local(path.points, frame);
    grow(points);
    scene.polylines.push_back({points, 2.0, drone_color(path.drone)});
  }
  std::map<int,
           std::pair<const planning::PlanFeatures::Sweep*, const planning::PlanFeatures::Sweep*>>
      ends;
  for (const auto& sw : features.sweeps) {
    auto& [first, last] = ends[sw.drone];
    if (!first || sw.line < first->line) first = &sw;
    if (!last || sw.line > last->line) last = &sw;
  }
  for (const auto& [drone, e] : ends) {
    scene.markers.push_back(
        {frame.to_local(e.first->start), 11 * mark, kInk, render::MarkerShape::disc});
    scene.markers.push_back(
        {frame.to_local(e.first->start), 7 * mark, drone_color(drone), render::MarkerShape::disc});
    scene.markers.push_back(
        {frame.to_local(e.second->end), 11 * mark, kInk, render::MarkerShape::square});
    scene.markers.push_back(
        {frame.to_local(e.second->end), 7 * mark, drone_color(drone), render::MarkerShape::square});
  }
}

/// A direction arrow in the middle of every k-th line of each drone, k the smallest keeping
/// neighbouring arrows about 28 px apart at this scale: a 130-line field keeps a readable few.
void add_line_arrows(render::Scene& scene, const planning::PlanFeatures& features,
                     const geometry::LocalFrame& frame, double px_per_m) {
  double spacing_m = 0;
  for (const auto& sw : features.sweeps) spacing_m = std::max(spacing_m, sw.footprint_width_m);
  // The footprint is wider than the spacing by the overlap: a smaller k errs towards fewer.
  const int every =
      std::max(1, static_cast<int>(std::ceil(28.0 / std::max(1e-9, spacing_m * 0.5 * px_per_m))));
  for (const auto& sw : features.sweeps) {
    if (sw.line % every != every / 2 % every) continue;
    const Point2 a = frame.to_local(sw.start), b = frame.to_local(sw.end);
    const double length_px = geometry::distance(a, b) * px_per_m;
    if (length_px < 20) continue;
    // arrow_every_px = the line's length: a single arrow, at its middle.
    scene.polylines.push_back({{a, b}, 2.0, drone_color(sw.drone), length_px});
  }
}

render::Color over(Color top, Color below) {
  return {top.r * top.a + below.r * (1 - top.a), top.g * top.a + below.g * (1 - top.a),
          top.b * top.a + below.b * (1 - top.a), 1};
}

std::vector<render::LegendEntry> legend_entries(const planning::PlanFeatures& features,
                                                const planning::PlanFigures& figures) {
  using render::SwatchKind;
  std::vector<render::LegendEntry> legend{
      {"area not covered", SwatchKind::fill, kArea, kOutline},
      {"area covered (camera footprint)", SwatchKind::fill, over(kFootprint, kArea), kOutline}};
  if (!features.no_fly.empty())
    legend.push_back({"no-fly zone", SwatchKind::fill, kNoFly, kNoFlyOutline});
  legend.push_back({features.drone_homes.empty() ? "home" : "home (a drone's own: its colour)",
                    SwatchKind::marker,
                    kInk,
                    {0, 0, 0, 0},
                    render::MarkerShape::triangle});
  legend.push_back(
      {"first line's start", SwatchKind::marker, kInk, {0, 0, 0, 0}, render::MarkerShape::disc});
  legend.push_back(
      {"last line's end", SwatchKind::marker, kInk, {0, 0, 0, 0}, render::MarkerShape::square});
  for (const auto& d : figures.drones)
    legend.push_back({drone_name(d), SwatchKind::line, drone_color(d.drone)});
  return legend;
}

}  // namespace

CoverageImage coverage_image(const planning::PlanFeatures& features,
                             const planning::PlanFigures& figures, int width_px, int height_px) {
  // A local frame at the first area vertex: drawing in metres, north up.
  const geometry::LocalFrame frame(features.area.front().front());
  CoverageImage out;
  out.frame_origin = frame.origin();
  // Text and marker sizes grow with the image: 12 px text up to 600 px high.
  const double text_h = std::max(12, height_px / 50);
  const double mark = text_h / 12;
  render::Scene& scene = out.scene;
  MapBounds bounds;
  auto grow = [&](const std::vector<Point2>& points) {
    for (const Point2& p : points) bounds.add(p);
  };
  render::FilledPolygon area{{}, kArea, kOutline, 1.5};
  for (const auto& ring : features.area) {
    area.rings.push_back(local(ring, frame));
    grow(area.rings.back());
  }
  scene.polygons.push_back(area);
  for (const auto& piece : features.area_pieces) {
    render::FilledPolygon p{{local(piece, frame)}, kArea, kOutline, 1.5};
    grow(p.rings.back());
    scene.polygons.push_back(p);
  }
  for (const auto& r : features.regions)
    scene.polygons.push_back({{local(r.ring, frame)}, {0, 0, 0, 0}, drone_color(r.drone), 2});
  for (const auto& sw : features.sweeps)
    scene.strips.push_back(
        {frame.to_local(sw.start), frame.to_local(sw.end), sw.footprint_width_m, kFootprint});
  for (const auto& zone : features.no_fly) {
    render::FilledPolygon z{{local(zone, frame)}, kNoFly, kNoFlyOutline, 1.5};
    grow(z.rings.back());
    scene.polygons.push_back(z);
  }
  add_paths(scene, features, frame, mark, grow);
  const Point2 home = frame.to_local(features.home);
  grow({home});
  scene.markers.push_back({home, 14 * mark, kInk, render::MarkerShape::triangle});
  for (const auto& h : features.drone_homes) {
    const Point2 at = frame.to_local(h.at);
    grow({at});
    scene.markers.push_back({at, 14 * mark, drone_color(h.drone), render::MarkerShape::triangle});
  }

  // Title lines, each fitted to the width left of the north arrow.
  std::vector<std::pair<std::string, Color>> title{
      {"coverage " + base::fixed_text(100 * figures.covered_fraction, 2) + " %   " +
           std::to_string(figures.lines) + " lines",
       kInk}};
  for (const auto& d : figures.drones) {
    if (title.size() > 6) break;
    title.push_back({drone_name(d) + ": " + base::fixed_text(d.path_length_m / 1000, 2) + " km, " +
                         planning::duration_text(d.flight_time_s),
                     drone_color(d.drone)});
  }
  double baseline = 8;
  for (const auto& [text, color] : title) {
    const double h = render::fitted_text_height(text, width_px - 80.0, text_h);
    baseline += h + 6;
    scene.labels.push_back({10, static_cast<int>(std::lround(baseline)), text, h, color});
    out.title_box.right_px =
        std::max(out.title_box.right_px, 10.0 + render::text_extent(text, h).width_px);
  }
  out.title_box.bottom_px = baseline + 0.4 * text_h;

  // The map where the legend leaves most room: beside it on the right or above it.
  const std::vector<render::LegendEntry> entries = legend_entries(features, figures);
  const double top = out.title_box.bottom_px + 8;
  const render::LegendSize legend =
      render::measure_legend(entries, 0.6 * width_px, height_px - top - 8, text_h);
  // Inset by half a home marker; the scale bar and its label below.
  const double inset = 8 * mark, bottom = height_px - 36 - text_h - inset;
  const render::View beside =
      render::fit_into(bounds.lo, bounds.hi,
                       {8 + inset, top + inset, width_px - 16 - legend.width_px - inset, bottom},
                       width_px, height_px);
  const render::View above =
      render::fit_into(bounds.lo, bounds.hi,
                       {8 + inset, top + inset, width_px - 8 - inset,
                        std::min(bottom, height_px - 16 - legend.height_px - inset)},
                       width_px, height_px);
  out.view = beside.px_per_m >= above.px_per_m ? beside : above;
  // Arrows now that the scale is known: one on every k-th line, k keeping them 28 px apart.
  add_line_arrows(scene, features, frame, out.view.px_per_m);

  const ScaleBar bar = add_scale_bar(scene, out.view, width_px, height_px, int(text_h));
  out.scale_bar_m = bar.length_m;
  out.scale_bar_px = bar.length_px;
  out.scale_bar_start_px = bar.start_px;
  add_north_arrow(scene, width_px, 2.5 * text_h + 20, int(text_h));

  // Legend, bottom right, between the scale bar's label and the title.
  const double bar_right =
      bar.start_px.x +
      std::max(
          bar.length_px,
          double(render::text_extent(base::fixed_text(bar.length_m, 0) + " m", text_h).width_px)) +
      12;
  out.legend_box =
      render::add_legend(scene, entries, {bar_right, top, width_px - 8.0, height_px - 8.0},
                         render::Corner::bottom_right, legend.text_height_px);
  return out;
}

}  // namespace swath::apps
