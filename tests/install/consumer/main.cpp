// survey_count FIELD CAMERA.yaml ALTITUDE_M: plans a one-drone survey with swath's planning
// library and prints its lines and photos, for comparison with `swath plan`'s files.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "swath/base/file_text.hpp"
#include "swath/geometry/field.hpp"
#include "swath/planning/camera.hpp"
#include "swath/planning/survey.hpp"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: survey_count FIELD CAMERA.yaml ALTITUDE_M\n");
    return 2;
  }
  try {
    swath::planning::SurveyRequest request;
    request.field = swath::geometry::read_field(argv[1]);
    request.camera = swath::planning::parse_camera(
        swath::base::read_text_file(argv[2], "camera file", 1 << 20), argv[2]);
    swath::planning::PhotogrammetryMode mode;
    mode.altitude_m = std::strtod(argv[3], nullptr);
    request.mode = mode;
    const swath::planning::SurveyPlan plan = swath::planning::plan_survey(request);
    std::size_t photos = 0;
    for (const auto& drone : plan.drones) photos += drone.photos.size();
    std::printf("lines %zu photos %zu\n", plan.sweep.lines.size(), photos);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "survey_count: %s\n", e.what());
    return 2;
  }
  return 0;
}
