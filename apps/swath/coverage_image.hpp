#pragma once
// The coverage picture of a plan.

#include <string>

#include "map_furniture.hpp"
#include "swath/planning/plan_features.hpp"
#include "swath/render/image.hpp"
#include "swath/render/legend.hpp"

namespace swath::apps {

struct CoverageImage {
  render::Scene scene;
  render::View view;
  geometry::GeoPoint frame_origin;      ///< the scene's local frame (metres east, north)
  double scale_bar_m = 0;               ///< the length the scale bar claims
  double scale_bar_px = 0;              ///< its length in the image
  geometry::Point2 scale_bar_start_px;  ///< left end, on the bar's centre line
  render::PixelBox title_box;           ///< the title lines, from the top-left corner
  render::PixelBox legend_box;          ///< the legend's backing box
};

/// The picture of a plan's features and figures: the same for `plan --render` (from the plan in
/// memory) and `render DIR` (from the files read back).
CoverageImage coverage_image(const planning::PlanFeatures& features,
                             const planning::PlanFigures& figures, int width_px, int height_px);

}  // namespace swath::apps
