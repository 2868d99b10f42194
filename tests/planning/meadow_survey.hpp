#pragma once
// The bundled meadow with the Sony QX1 in photogrammetry mode: the real field planning tests use.

#include <string>

#include "swath/geometry/field.hpp"
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

}  // namespace swath::test
