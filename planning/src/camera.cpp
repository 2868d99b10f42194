#include "swath/planning/camera.hpp"
#include "swath/base/file_text.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "swath/base/input_error.hpp"
#include "swath/base/yaml_input.hpp"
#include "swath/planning/imaging.hpp"
#include "swath/planning/limits.hpp"

namespace swath::planning {
namespace {

using base::InputError;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// The number at `node`, inside its plausible range; errors name the file, line and key.
double number(const YAML::Node& node, const std::string& key, const std::string& source,
              const base::Range& range) {
  const std::string where = source + ": line " + std::to_string(node.Mark().line + 1) + ": " + key;
  double value = 0;
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    throw InputError(where + " must be a number");
  }
  base::check_range(value, range, where);
  return value;
}

std::string read_text(const std::filesystem::path& path) {
  return base::read_text_file(path, "camera file", base::kMaxConfigFileBytes);
}

}  // namespace

namespace {

// The optional DJI WPML enumerations: dji_drone_enum and dji_payload_enum together (a KMZ names
// both or neither), dji_drone_sub_enum optional; whole numbers in [0, 65535] as WPML's ints.
std::optional<DjiEnums> dji_enums(const YAML::Node& root, const std::string& source) {
  static constexpr base::Range kEnum{0, 65535, "", "a DJI WPML enumeration value"};
  auto integer = [&](const char* key) {
    const double v = number(root[key], key, source, kEnum);
    if (v != std::floor(v))
      throw InputError(source + ": line " + std::to_string(root[key].Mark().line + 1) + ": " + key +
                       " must be a whole number");
    return static_cast<int>(v);
  };
  if (!root["dji_drone_enum"] && !root["dji_payload_enum"]) {
    if (root["dji_drone_sub_enum"])
      throw InputError(source + ": dji_drone_sub_enum needs dji_drone_enum and dji_payload_enum");
    return std::nullopt;
  }
  if (!root["dji_drone_enum"] || !root["dji_payload_enum"])
    throw InputError(source + ": dji_drone_enum and dji_payload_enum go together");
  DjiEnums e;
  e.drone = integer("dji_drone_enum");
  e.payload = integer("dji_payload_enum");
  if (root["dji_drone_sub_enum"]) e.drone_sub = integer("dji_drone_sub_enum");
  return e;
}

Camera camera_from_yaml(const std::string& yaml_text, const std::string& source) {
  const YAML::Node root = base::load_yaml(yaml_text, source);
  if (!root.IsMap())
    throw InputError(source + ": a camera file is a YAML mapping of name, sensor and image sizes");
  static const std::set<std::string> known{"name",
                                           "sensor_width_mm",
                                           "sensor_height_mm",
                                           "focal_length_mm",
                                           "image_width_px",
                                           "image_height_px",
                                           "min_trigger_interval_s",
                                           "dji_drone_enum",
                                           "dji_drone_sub_enum",
                                           "dji_payload_enum"};
  base::check_plain_unique_keys(root, source);
  for (const auto& kv : root) {
    const std::string key = kv.first.Scalar();
    if (!known.count(key))
      throw InputError(source + ": line " + std::to_string(kv.first.Mark().line + 1) +
                       ": unknown key '" + key + "'");
  }
  auto required = [&](const char* key) {
    if (!root[key]) throw InputError(source + ": the camera has no " + std::string(key));
    return root[key];
  };
  Camera c;
  c.name = required("name").as<std::string>();
  c.sensor_width_mm =
      number(required("sensor_width_mm"), "sensor_width_mm", source, limits::kSensorSize_mm);
  c.sensor_height_mm =
      number(required("sensor_height_mm"), "sensor_height_mm", source, limits::kSensorSize_mm);
  c.focal_length_mm =
      number(required("focal_length_mm"), "focal_length_mm", source, limits::kFocalLength_mm);
  const double w =
      number(required("image_width_px"), "image_width_px", source, limits::kImageSize_px);
  const double h =
      number(required("image_height_px"), "image_height_px", source, limits::kImageSize_px);
  if (w != std::floor(w) || h != std::floor(h))
    throw InputError(source +
                     ": image_width_px and image_height_px must be whole numbers of pixels");
  c.image_width_px = static_cast<int>(w);
  c.image_height_px = static_cast<int>(h);
  if (root["min_trigger_interval_s"])
    c.min_trigger_interval_s = number(root["min_trigger_interval_s"], "min_trigger_interval_s",
                                      source, limits::kTriggerInterval_s);
  c.dji = dji_enums(root, source);
  validate_camera(c, source);
  return c;
}

}  // namespace

Camera parse_camera(const std::string& yaml_text, const std::string& source) {
  return base::yaml_guard(source, [&] { return camera_from_yaml(yaml_text, source); });
}

std::vector<CameraEntry> camera_database(const std::filesystem::path& directory) {
  std::vector<CameraEntry> entries;
  std::error_code ec;
  for (const auto& file : std::filesystem::directory_iterator(directory, ec)) {
    if (file.path().extension() != ".yaml") continue;
    entries.push_back(
        {file.path().stem().string(), parse_camera(read_text(file.path()), file.path().string())});
  }
  std::sort(entries.begin(), entries.end(),
            [](const CameraEntry& a, const CameraEntry& b) { return a.id < b.id; });
  return entries;
}

Camera find_camera(const std::string& spec, const std::filesystem::path& database_directory) {
  std::error_code ec;
  if (spec.find('/') != std::string::npos || spec.ends_with(".yaml") || spec.ends_with(".yml")) {
    if (!std::filesystem::is_regular_file(spec, ec))
      throw InputError(spec + ": cannot open the camera file");
    return parse_camera(read_text(spec), spec);
  }
  // An id names its file: parse that one, not the whole database (16 files were a fifth of a
  // small plan's time). A camera name still searches every file.
  const std::filesystem::path by_id = database_directory / (lower(spec) + ".yaml");
  if (std::filesystem::is_regular_file(by_id, ec))
    return parse_camera(read_text(by_id), by_id.string());
  const std::vector<CameraEntry> entries = camera_database(database_directory);
  for (const CameraEntry& e : entries)
    if (e.id == lower(spec) || lower(e.camera.name) == lower(spec)) return e.camera;
  // Suggest ids that share the first word (the brand) or contain the spec.
  std::string suggestions;
  const std::string brand = lower(spec.substr(0, spec.find_first_of(" -")));
  for (const CameraEntry& e : entries)
    if (e.id.find(lower(spec)) != std::string::npos || e.id.rfind(brand, 0) == 0)
      suggestions += (suggestions.empty() ? "" : ", ") + e.id;
  throw InputError("--camera " + spec + ": no such camera in " + database_directory.string() +
                   (suggestions.empty() ? "" : " (did you mean " + suggestions + "?)") +
                   "; 'swath cameras' lists them, or give a camera YAML file");
}

}  // namespace swath::planning
