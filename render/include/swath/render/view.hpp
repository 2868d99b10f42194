#pragma once

#include "swath/geometry/point.hpp"

namespace swath::render {

/// World metres (x east, y north) to image pixels (x right, y down), same scale on both axes.
struct View {
  double px_per_m = 1.0;
  double origin_x_m = 0.0, origin_y_m = 0.0;  ///< world point at pixel (0, 0)... of the top-left
  int width_px = 0, height_px = 0;

  geometry::Point2 to_pixel(geometry::Point2 world) const {
    return {(world.x - origin_x_m) * px_per_m, (origin_y_m - world.y) * px_per_m};
  }
};

/// The largest scale that fits [min, max] into the image with `margin_px` on every side, centred;
/// the aspect ratio is kept. Precondition: width_px, height_px > 2 margin_px.
View fit(geometry::Point2 min, geometry::Point2 max, int width_px, int height_px, int margin_px);

}  // namespace swath::render
