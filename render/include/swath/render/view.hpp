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

/// A rectangle in image pixels (x right, y down); left/top inclusive, right/bottom exclusive.
struct PixelBox {
  double left_px = 0, top_px = 0, right_px = 0, bottom_px = 0;
  bool inside(int width_px, int height_px) const {
    return left_px >= 0 && top_px >= 0 && right_px <= width_px && bottom_px <= height_px;
  }
  bool overlaps(const PixelBox& o) const {
    return left_px < o.right_px && o.left_px < right_px && top_px < o.bottom_px &&
           o.top_px < bottom_px;
  }
};

/// The largest scale that fits [min, max] into the image with `margin_px` on every side, centred;
/// the aspect ratio is kept. Precondition: width_px, height_px > 2 margin_px.
View fit(geometry::Point2 min, geometry::Point2 max, int width_px, int height_px, int margin_px);

/// The largest scale that fits [min, max] into `box` of a width_px x height_px image, centred in
/// the box. Precondition: the box has a positive width and height.
View fit_into(geometry::Point2 min, geometry::Point2 max, const PixelBox& box, int width_px,
              int height_px);

}  // namespace swath::render
