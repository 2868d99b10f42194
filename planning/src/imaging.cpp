#include "swath/planning/imaging.hpp"

#include <cmath>

#include "swath/base/input_error.hpp"
#include "swath/planning/limits.hpp"

namespace swath::planning {
namespace {

using base::InputError;

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

// Spacing and trigger distance follow from camera, altitude and overlaps; either one tiny would
// ask for millions of lines or photos (and a trigger distance that rounds to 0 means "stop
// triggering" to MAVLink), so they are bounded too.
void check_derived(const Imaging& im, const std::string& where) {
  base::check_range(
      im.line_spacing_m, limits::kSpacing_m,
      where + ": the line spacing that follows from the camera, altitude and overlap,");
  base::check_range(im.trigger_distance_m, limits::kSpacing_m,
                    where +
                        ": the trigger distance that follows from the camera, altitude and "
                        "overlap,");
}

}  // namespace

void validate_camera(const Camera& c, const std::string& where) {
  base::check_range(c.sensor_width_mm, limits::kSensorSize_mm, where + ": sensor_width_mm");
  base::check_range(c.sensor_height_mm, limits::kSensorSize_mm, where + ": sensor_height_mm");
  base::check_range(c.focal_length_mm, limits::kFocalLength_mm, where + ": focal_length_mm");
  base::check_range(c.image_width_px, limits::kImageSize_px, where + ": image_width_px");
  base::check_range(c.image_height_px, limits::kImageSize_px, where + ": image_height_px");
}

double horizontal_fov_rad(const Camera& c) {
  return 2 * std::atan(c.sensor_width_mm / (2 * c.focal_length_mm));
}

Imaging detection_imaging(const Camera& c, const DetectionMode& m, ImageOrientation orientation,
                          const std::string& where) {
  validate_camera(c, where);
  base::check_range(m.pattern_width_m, limits::kPattern_m, where + ": the pattern width");
  base::check_range(m.pattern_height_m, limits::kPattern_m, where + ": the pattern height");
  base::check_range(m.min_pixels, limits::kMinPixels, where + ": the pixels on the pattern");
  base::check_range(m.overlap, limits::kDetectionOverlap, where + ": the overlap");
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
  check_derived(im, where);
  return im;
}

Imaging photogrammetry_imaging(const Camera& c, const PhotogrammetryMode& m,
                               ImageOrientation orientation, const std::string& where) {
  validate_camera(c, where);
  require(m.altitude_m.has_value() != m.gsd_m.has_value(), where,
          "give either an altitude or a GSD, not both");
  limits::check_overlap(m.side_overlap, where + ": the side overlap");
  limits::check_overlap(m.front_overlap, where + ": the front overlap");
  double altitude = 0;
  if (m.altitude_m) {
    base::check_range(*m.altitude_m, limits::kAltitude_m, where + ": the altitude");
    altitude = *m.altitude_m;
  } else {
    base::check_range(*m.gsd_m * 100, limits::kGsd_cm, where + ": the GSD");
    altitude = *m.gsd_m * c.focal_length_mm * c.image_width_px / c.sensor_width_mm;
    base::check_range(altitude, limits::kAltitude_m,
                      where + ": the altitude that gives this GSD with this camera,");
  }
  Imaging im;
  set_footprint(im, c, altitude, orientation);
  im.line_spacing_m = im.footprint_across_m * (1 - m.side_overlap);
  im.trigger_distance_m = im.footprint_along_m * (1 - m.front_overlap);
  check_derived(im, where);
  return im;
}

}  // namespace swath::planning
