#include "swath/planning/imaging.hpp"

#include <cmath>

#include "swath/base/input_error.hpp"

namespace swath::planning {
namespace {

using base::InputError;

bool positive(double v) {
  return std::isfinite(v) && v > 0;
}

void require(bool ok, const std::string& where, const std::string& what) {
  if (!ok) throw InputError(where + ": " + what);
}

// Footprint of one photo at `altitude_m` (square pixels: the GSD comes from the image width).
void set_footprint(Imaging& im, const Camera& c, double altitude_m, ImageOrientation orientation) {
  im.altitude_m = altitude_m;
  im.gsd_m = c.sensor_width_mm * altitude_m / (c.focal_length_mm * c.image_width_px);
  const double ground_w = c.image_width_px * im.gsd_m;
  const double ground_h = c.image_height_px * im.gsd_m;
  im.footprint_across_m = orientation == ImageOrientation::landscape ? ground_w : ground_h;
  im.footprint_along_m = orientation == ImageOrientation::landscape ? ground_h : ground_w;
}

}  // namespace

void validate_camera(const Camera& c, const std::string& where) {
  require(positive(c.sensor_width_mm), where, "sensor_width_mm must be > 0");
  require(positive(c.sensor_height_mm), where, "sensor_height_mm must be > 0");
  require(positive(c.focal_length_mm), where, "focal_length_mm must be > 0");
  require(c.image_width_px > 0 && c.image_height_px > 0, where,
          "the image size must be > 0 pixels");
}

double horizontal_fov_rad(const Camera& c) {
  return 2 * std::atan(c.sensor_width_mm / (2 * c.focal_length_mm));
}

Imaging detection_imaging(const Camera& c, const DetectionMode& m, ImageOrientation orientation,
                          const std::string& where) {
  validate_camera(c, where);
  require(positive(m.pattern_width_m) && positive(m.pattern_height_m), where,
          "the pattern size must be > 0 m");
  require(positive(m.min_pixels), where, "the minimum pixels on the pattern must be > 0");
  require(m.overlap >= 0 && m.overlap <= 1, where, "the overlap must be in [0, 1]");
  const double pattern = std::min(m.pattern_width_m, m.pattern_height_m);
  Imaging im;
  im.h_max_m =
      pattern * c.image_width_px / (2 * m.min_pixels * std::tan(horizontal_fov_rad(c) / 2));
  im.h_min_m = *im.h_max_m / 2;
  const double altitude = *im.h_max_m * (1 + m.overlap) / 2;
  set_footprint(im, c, altitude, orientation);
  // step: half the footprint across at h_max, i.e. the footprint at h divided by (1 + overlap).
  im.line_spacing_m = im.footprint_across_m / (1 + m.overlap);
  im.trigger_distance_m = im.footprint_along_m / (1 + m.overlap);
  return im;
}

Imaging photogrammetry_imaging(const Camera& c, const PhotogrammetryMode& m,
                               ImageOrientation orientation, const std::string& where) {
  validate_camera(c, where);
  require(m.altitude_m.has_value() != m.gsd_m.has_value(), where,
          "give either an altitude or a GSD, not both");
  require(m.side_overlap >= 0 && m.side_overlap < 1, where, "the side overlap must be in [0, 1)");
  require(m.front_overlap >= 0 && m.front_overlap < 1, where,
          "the front overlap must be in [0, 1)");
  double altitude = 0;
  if (m.altitude_m) {
    require(positive(*m.altitude_m), where, "the altitude must be > 0 m");
    altitude = *m.altitude_m;
  } else {
    require(positive(*m.gsd_m), where, "the GSD must be > 0");
    altitude = *m.gsd_m * c.focal_length_mm * c.image_width_px / c.sensor_width_mm;
  }
  Imaging im;
  set_footprint(im, c, altitude, orientation);
  im.line_spacing_m = im.footprint_across_m * (1 - m.side_overlap);
  im.trigger_distance_m = im.footprint_along_m * (1 - m.front_overlap);
  return im;
}

}  // namespace swath::planning
