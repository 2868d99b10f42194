#pragma once
// Line charts of time series (the energy tool's power, state of charge, parameters), drawn with
// the same scenes as the maps.

#include <string>
#include <vector>

#include "swath/render/legend.hpp"
#include "swath/render/scene.hpp"

namespace swath::render {

struct Series {
  std::string name;
  std::vector<double> x, y;  ///< same length
  Color color;
  double width_px = 2;
};

struct ChartSpec {
  std::string title, x_label, y_label;
  std::vector<Series> series;
};

/// Where the plot area lies and how data maps to it (for labels and tests).
struct ChartLayout {
  double left_px, top_px, right_px, bottom_px;  ///< the plot area
  double x_min, x_max, y_min, y_max;            ///< data range shown (rounded out to ticks)
  std::vector<double> x_ticks, y_ticks;
  PixelBox legend;  ///< where the legend was drawn
  double to_x_px(double x) const {
    return left_px + (x - x_min) / (x_max - x_min) * (right_px - left_px);
  }
  double to_y_px(double y) const {
    return bottom_px - (y - y_min) / (y_max - y_min) * (bottom_px - top_px);
  }
};

/// A scene (screen layer and labels only) of the chart at width x height pixels: axes with round
/// ticks and their numbers, axis labels, one polyline per series, a legend (series without a
/// name are drawn but not listed), the title. Draw it with
/// draw() and any view of that size. Throws std::invalid_argument if a series' x and y differ in
/// length or there is no finite point.
Scene chart_scene(const ChartSpec& spec, int width_px, int height_px,
                  ChartLayout* layout = nullptr);

/// Adds `part` (a chart scene's screen layer and labels) to `into`, moved down by `dy_px`: charts
/// stacked in one picture.
void stack_scene(Scene& into, const Scene& part, double dy_px);

/// Round tick values covering [lo, hi]: steps of 1, 2 or 5 times a power of ten, about `count`.
std::vector<double> nice_ticks(double lo, double hi, int count);

}  // namespace swath::render
