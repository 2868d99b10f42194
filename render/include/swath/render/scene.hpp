#pragma once
// What to draw, as plain data in world metres (render knows nothing of missions).

#include <cstdint>
#include <string>
#include <vector>

#include "swath/geometry/point.hpp"

namespace swath::render {

/// Straight (non-premultiplied) colour, each channel in [0, 1].
struct Color {
  float r = 0, g = 0, b = 0, a = 1;
};

/// A filled area; rings by the even-odd rule (holes are simply further rings).
struct FilledPolygon {
  std::vector<std::vector<geometry::Point2>> rings;
  Color fill;
  Color outline{0, 0, 0, 0};  ///< alpha 0: no outline
  double outline_px = 1.0;
};

/// A band of `width_m` centred on the segment a-b (a camera footprint along a flight line).
struct Strip {
  geometry::Point2 a, b;
  double width_m = 0;
  Color color;
};

struct Polyline {
  std::vector<geometry::Point2> points;
  double width_px = 2.0;
  Color color;
  double arrow_every_px = 0.0;  ///< > 0: a direction arrowhead about every so many pixels
};

enum class MarkerShape { disc, square, triangle };

struct Marker {
  geometry::Point2 at;
  double size_px = 10;
  Color color;
  MarkerShape shape = MarkerShape::disc;
};

/// Text anchored at a pixel position of the final image (top-left origin), drawn anti-aliased.
struct Label {
  int x_px = 0, y_px = 0;  ///< baseline start
  std::string text;
  double height_px = 14;
  Color color{0, 0, 0, 1};
};

/// A picture under everything else (a basemap), the final image's size: 8-bit RGB, rows top to
/// bottom. Empty: the background colour.
struct Backdrop {
  int width_px = 0, height_px = 0;
  std::vector<std::uint8_t> rgb;
};

/// Draw order: the backdrop, polygons, strips, polylines, markers (world metres), then the screen
/// layer (pixel coordinates of the final image: legend swatches, scale bar, north arrow) and labels
/// on top.
struct Scene {
  Color background{1, 1, 1, 1};
  Backdrop backdrop;  ///< drawn when its size is the image's
  std::vector<FilledPolygon> polygons;
  std::vector<Strip> strips;
  std::vector<Polyline> polylines;
  std::vector<Marker> markers;
  std::vector<FilledPolygon> screen_polygons;  ///< points in pixels (x right, y down)
  std::vector<Polyline> screen_polylines;      ///< points in pixels
  std::vector<Label> labels;
};

}  // namespace swath::render
