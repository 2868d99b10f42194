#pragma once
// What every map picture carries: a scale bar of a round length and a north arrow.

#include <string>
#include <utility>

#include "swath/render/scene.hpp"
#include "swath/render/view.hpp"

namespace swath::apps {

struct ScaleBar {
  double length_m = 0;        ///< the length the bar claims
  double length_px = 0;       ///< its length in the image
  geometry::Point2 start_px;  ///< left end, on the bar's centre line
};

/// The bounding box of what a map shows, grown point by point.
struct MapBounds {
  geometry::Point2 lo{1e300, 1e300}, hi{-1e300, -1e300};
  void add(geometry::Point2 p) {
    lo = {p.x < lo.x ? p.x : lo.x, p.y < lo.y ? p.y : lo.y};
    hi = {p.x > hi.x ? p.x : hi.x, p.y > hi.y ? p.y : hi.y};
  }
};

/// "WxH" pixels (64..5000 each); throws base::InputError naming --size.
std::pair<int, int> parse_size(const std::string& text);

/// 1, 2 or 5 times a power of ten, at most `metres`.
double nice_length(double metres);

/// A bar of a round length about a quarter of the width, bottom left, labelled in metres.
ScaleBar add_scale_bar(render::Scene& scene, const render::View& view, int width_px, int height_px,
                       int text_h);

/// A north arrow near the top right corner, its tip at `y_px` - 18.
void add_north_arrow(render::Scene& scene, int width_px, double y_px, int text_h);

}  // namespace swath::apps
