#pragma once
// Altitude, footprint and spacing from a camera (docs/swath-plan.md, paper 001 eq. 4-6).

#include <optional>

#include "swath/planning/camera.hpp"

namespace swath::planning {

/// Which image side lies across the flight line.
enum class ImageOrientation { landscape, portrait };

/// What a survey flies at and how its photos tile the ground. Lengths in metres on flat ground.
struct Imaging {
  double altitude_m = 0.0;          ///< above the take-off point
  double gsd_m = 0.0;               ///< ground sample distance, metres per pixel (square pixels)
  double footprint_across_m = 0.0;  ///< one photo's ground extent across the flight line
  double footprint_along_m = 0.0;   ///< and along it
  double line_spacing_m = 0.0;  ///< distance between adjacent flight lines (<= footprint_across_m)
  double trigger_distance_m = 0.0;  ///< distance flown between two photos
  std::optional<double> h_min_m;    ///< detection mode: lowest useful altitude
  std::optional<double>
      h_max_m;  ///< detection mode: highest altitude that still resolves the pattern
};

/// Detection mode (paper 001 §V-C): a ground pattern of W x H metres must span at least
/// `min_pixels` pixels. h_max = min(W, H) * image_width / (2 min_pixels tan(fov / 2)),
/// fov = 2 atan(sensor_width / (2 f)), h_min = h_max / 2, line spacing ("step") = half the
/// footprint width at h_max, altitude h = h_max (1 + overlap) / 2, so the footprint width at h is
/// step (1 + overlap): at overlap 0 adjacent footprints touch, at 1 each point is seen from two
/// lines. Photos along the line overlap alike: trigger distance = footprint_along / (1 + overlap).
struct DetectionMode {
  double pattern_width_m = 0.0;   ///< > 0
  double pattern_height_m = 0.0;  ///< > 0
  double min_pixels = 0.0;        ///< > 0
  double overlap = 0.0;           ///< in [0, 1]
};

/// Photogrammetry mode (QGroundControl's survey): altitude or GSD given, then
/// GSD = sensor_width h / (f image_width), footprint = image size x GSD (width across the line in
/// landscape), spacing = footprint_across (1 - side_overlap), trigger = footprint_along (1 -
/// front_overlap).
struct PhotogrammetryMode {
  std::optional<double> altitude_m;  ///< > 0; exactly one of altitude_m and gsd_m
  std::optional<double> gsd_m;       ///< > 0, metres per pixel
  double side_overlap = 0.7;         ///< in [0, 1)
  double front_overlap = 0.7;        ///< in [0, 1)
};

/// Throws base::InputError for a camera or mode outside limits.hpp's ranges, or a line spacing
/// or trigger distance that follows from them outside limits::kSpacing_m; `where` prefixes the
/// message.
Imaging detection_imaging(const Camera& camera, const DetectionMode& mode,
                          ImageOrientation orientation,
                          const std::string& where = "detection mode");
Imaging photogrammetry_imaging(const Camera& camera, const PhotogrammetryMode& mode,
                               ImageOrientation orientation,
                               const std::string& where = "photogrammetry mode");

/// Horizontal field of view across the image width, radians.
double horizontal_fov_rad(const Camera& camera);

/// Throws base::InputError unless every figure of the camera is inside limits.hpp's ranges.
void validate_camera(const Camera& camera, const std::string& where);

}  // namespace swath::planning
