#pragma once
// The coverage picture of a plan, from its mission.geojson and summary.json (so `plan --render`
// and `render DIR` draw the same thing).

#include <string>

#include "map_furniture.hpp"
#include "swath/render/image.hpp"

namespace swath::apps {

struct CoverageImage {
  render::Scene scene;
  render::View view;
  double scale_bar_m = 0;               ///< the length the scale bar claims
  double scale_bar_px = 0;              ///< its length in the image
  geometry::Point2 scale_bar_start_px;  ///< left end, on the bar's centre line
};

/// Throws base::InputError if the texts are not a swath plan (file names in `source`).
CoverageImage coverage_image(const std::string& geojson_text, const std::string& summary_text,
                             int width_px, int height_px, const std::string& source);

}  // namespace swath::apps
