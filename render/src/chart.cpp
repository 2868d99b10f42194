#include "swath/render/chart.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "swath/render/image.hpp"

namespace swath::render {
namespace {

using geometry::Point2;

std::string tick_text(double v, double step) {
  std::ostringstream s;
  const int decimals = step >= 1 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  s.setf(std::ios::fixed);
  s.precision(decimals);
  s << (std::abs(v) < step * 1e-9 ? 0.0 : v);
  return s.str();
}

}  // namespace

void stack_scene(Scene& into, const Scene& part, double dy_px) {
  for (auto p : part.screen_polygons) {
    for (auto& ring : p.rings)
      for (auto& pt : ring) pt.y += dy_px;
    into.screen_polygons.push_back(std::move(p));
  }
  for (auto l : part.screen_polylines) {
    for (auto& pt : l.points) pt.y += dy_px;
    into.screen_polylines.push_back(std::move(l));
  }
  for (auto label : part.labels) {
    label.y_px += static_cast<int>(std::lround(dy_px));
    into.labels.push_back(std::move(label));
  }
}

std::vector<double> nice_ticks(double lo, double hi, int count) {
  if (!(hi > lo)) hi = lo + 1;
  const double raw = (hi - lo) / std::max(1, count);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  double step = p;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) {
      step = m * p;
      break;
    }
  std::vector<double> ticks;
  for (double t = std::floor(lo / step) * step; t <= std::ceil(hi / step) * step + step * 1e-9;
       t += step)
    ticks.push_back(t);
  return ticks;
}

Scene chart_scene(const ChartSpec& spec, int width_px, int height_px, ChartLayout* layout_out) {
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const Series& s : spec.series) {
    if (s.x.size() != s.y.size())
      throw std::invalid_argument("chart: series '" + s.name +
                                  "' has x and y of different lengths");
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
        x0 = std::min(x0, s.x[i]), x1 = std::max(x1, s.x[i]), y0 = std::min(y0, s.y[i]),
        y1 = std::max(y1, s.y[i]);
      }
  }
  if (!std::isfinite(x0)) throw std::invalid_argument("chart: no finite point to draw");
  const double text_h = std::max(11.0, height_px / 40.0);
  ChartLayout l;
  l.x_ticks = nice_ticks(x0, x1, 6);
  l.y_ticks = nice_ticks(y0, y1, 5);
  l.x_min = l.x_ticks.front(), l.x_max = l.x_ticks.back();
  l.y_min = l.y_ticks.front(), l.y_max = l.y_ticks.back();
  l.left_px = 8 * text_h;
  l.right_px = width_px - 2 * text_h;
  l.top_px = 3 * text_h;
  l.bottom_px = height_px - 4 * text_h;

  Scene scene;
  const Color ink{0.1f, 0.1f, 0.1f, 1}, grid{0.85f, 0.85f, 0.85f, 1};
  for (double t : l.y_ticks) {
    const double y = l.to_y_px(t);
    scene.screen_polylines.push_back({{{l.left_px, y}, {l.right_px, y}}, 1, grid});
    scene.screen_polylines.push_back({{{l.left_px - 6, y}, {l.left_px, y}}, 1.5, ink});
    scene.labels.push_back({static_cast<int>(text_h), static_cast<int>(y + text_h / 2),
                            tick_text(t, l.y_ticks.size() > 1 ? l.y_ticks[1] - l.y_ticks[0] : 1),
                            text_h, ink});
  }
  for (double t : l.x_ticks) {
    const double x = l.to_x_px(t);
    scene.screen_polylines.push_back({{{x, l.top_px}, {x, l.bottom_px}}, 1, grid});
    scene.screen_polylines.push_back({{{x, l.bottom_px}, {x, l.bottom_px + 6}}, 1.5, ink});
    scene.labels.push_back(
        {static_cast<int>(x - text_h), static_cast<int>(l.bottom_px + 1.8 * text_h),
         tick_text(t, l.x_ticks.size() > 1 ? l.x_ticks[1] - l.x_ticks[0] : 1), text_h, ink});
  }
  scene.screen_polylines.push_back(
      {{{l.left_px, l.top_px}, {l.left_px, l.bottom_px}, {l.right_px, l.bottom_px}}, 1.5, ink});
  for (const Series& s : spec.series) {
    Polyline line{{}, s.width_px, s.color};
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i]))
        line.points.push_back({l.to_x_px(s.x[i]), l.to_y_px(s.y[i])});
    scene.screen_polylines.push_back(std::move(line));
  }
  // Title and axis labels measured: the title shrinks to the image's width, the x label is
  // centred under the plot.
  scene.labels.push_back(
      {static_cast<int>(l.left_px), static_cast<int>(2 * text_h), spec.title,
       fitted_text_height(spec.title, width_px - l.left_px - text_h, text_h * 1.2), ink});
  const TextExtent x_label = text_extent(spec.x_label, text_h);
  scene.labels.push_back({static_cast<int>((l.left_px + l.right_px - x_label.width_px) / 2),
                          static_cast<int>(height_px - text_h), spec.x_label, text_h, ink});
  scene.labels.push_back({static_cast<int>(text_h), static_cast<int>(l.top_px - text_h * 0.9),
                          spec.y_label, text_h, ink});
  // Legend, top right inside the plot, measured and boxed.
  std::vector<LegendEntry> legend;
  for (const Series& s : spec.series)
    if (!s.name.empty()) legend.push_back({s.name, SwatchKind::line, s.color});
  l.legend =
      add_legend(scene, legend, {l.left_px + 4, l.top_px + 4, l.right_px - 4, l.bottom_px - 4},
                 Corner::top_right, text_h);
  if (layout_out) *layout_out = l;
  return scene;
}

}  // namespace swath::render
