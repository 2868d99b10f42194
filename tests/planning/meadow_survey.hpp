#pragma once
// The bundled meadow with the Sony QX1 in photogrammetry mode and the vineyard with the Phantom 4
// Pro: the real fields planning tests use (local_field.hpp: fields drawn in local metres).

#include <string>

#include "local_field.hpp"
#include "swath/geometry/field.hpp"
#include "swath/geometry/polygon.hpp"
#include "swath/planning/camera.hpp"
#include "swath/planning/survey.hpp"

namespace swath::test {

inline planning::SurveyRequest meadow_request(double altitude_m) {
  planning::SurveyRequest r;
  r.field = geometry::read_field(std::string(SWATH_SOURCE_DIR) + "/share/fields/meadow.geojson");
  r.camera =
      planning::find_camera("sony-ilce-qx1", std::string(SWATH_SOURCE_DIR) + "/share/cameras");
  planning::PhotogrammetryMode m;
  m.altitude_m = altitude_m;
  r.mode = m;
  return r;
}

/// The bundled vineyard (a notch and a pond) with the DJI Phantom 4 Pro at 60 m, home to its
/// south-west, as the README's examples plan it.
inline planning::SurveyRequest vineyard_request() {
  planning::SurveyRequest r;
  r.field = geometry::read_field(std::string(SWATH_SOURCE_DIR) + "/share/fields/vineyard.kml");
  r.camera =
      planning::find_camera("dji-phantom-4-pro", std::string(SWATH_SOURCE_DIR) + "/share/cameras");
  planning::PhotogrammetryMode m;
  m.altitude_m = 60;
  r.mode = m;
  r.home = geometry::GeoPoint{46.2276, 7.5917, 0};
  return r;
}

}  // namespace swath::test
