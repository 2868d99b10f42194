#include "cameras_command.hpp"

#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "data_dir.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/planning/camera.hpp"

namespace swath::apps {

using base::fixed_text;

void CamerasCommand::setup(CLI::App& app) {
  app.add_flag("--json", json_, "Print a JSON array instead of a table");
}

int CamerasCommand::run() {
  const auto entries = planning::camera_database(share_dir() / "cameras");
  if (json_) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const auto& e : entries) {
      const planning::Camera& c = e.camera;
      list.push_back({{"id", e.id},
                      {"name", c.name},
                      {"sensor_width_mm", c.sensor_width_mm},
                      {"sensor_height_mm", c.sensor_height_mm},
                      {"focal_length_mm", c.focal_length_mm},
                      {"image_width_px", c.image_width_px},
                      {"image_height_px", c.image_height_px},
                      {"min_trigger_interval_s",
                       c.min_trigger_interval_s ? nlohmann::ordered_json(*c.min_trigger_interval_s)
                                                : nlohmann::ordered_json()}});
    }
    std::cout << base::json_text(list, 2) << '\n';
    return base::kExitSuccess;
  }
  std::printf("%-22s %-30s %13s %8s %12s %9s\n", "id", "name", "sensor mm", "focal mm", "image px",
              "min dt s");
  for (const auto& e : entries) {
    const planning::Camera& c = e.camera;
    const std::string sensor =
        fixed_text(c.sensor_width_mm, 2) + "x" + fixed_text(c.sensor_height_mm, 2);
    const std::string image =
        std::to_string(c.image_width_px) + "x" + std::to_string(c.image_height_px);
    std::printf("%-22s %-30s %13s %8s %12s %9s\n", e.id.c_str(), c.name.c_str(), sensor.c_str(),
                fixed_text(c.focal_length_mm, 2).c_str(), image.c_str(),
                c.min_trigger_interval_s ? fixed_text(*c.min_trigger_interval_s, 1).c_str() : "-");
  }
  return base::kExitSuccess;
}

}  // namespace swath::apps
