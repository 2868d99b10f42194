#include "swath/render/view.hpp"

#include <algorithm>

namespace swath::render {

View fit(geometry::Point2 min, geometry::Point2 max, int width_px, int height_px, int margin_px) {
  View v;
  v.width_px = width_px;
  v.height_px = height_px;
  const double w = std::max(max.x - min.x, 1e-9), h = std::max(max.y - min.y, 1e-9);
  v.px_per_m = std::min((width_px - 2.0 * margin_px) / w, (height_px - 2.0 * margin_px) / h);
  // Centre the extent: the pixel centre of the image shows the extent's centre.
  v.origin_x_m = (min.x + max.x) / 2 - width_px / 2.0 / v.px_per_m;
  v.origin_y_m = (min.y + max.y) / 2 + height_px / 2.0 / v.px_per_m;
  return v;
}

View fit_into(geometry::Point2 min, geometry::Point2 max, const PixelBox& box, int width_px,
              int height_px) {
  View v;
  v.width_px = width_px;
  v.height_px = height_px;
  const double w = std::max(max.x - min.x, 1e-9), h = std::max(max.y - min.y, 1e-9);
  v.px_per_m = std::min((box.right_px - box.left_px) / w, (box.bottom_px - box.top_px) / h);
  v.origin_x_m = (min.x + max.x) / 2 - (box.left_px + box.right_px) / 2 / v.px_per_m;
  v.origin_y_m = (min.y + max.y) / 2 + (box.top_px + box.bottom_px) / 2 / v.px_per_m;
  return v;
}

}  // namespace swath::render
