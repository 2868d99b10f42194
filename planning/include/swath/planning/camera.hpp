#pragma once
// Cameras: the YAML file format and the database in share/cameras/.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "swath/missions/export_types.hpp"

namespace swath::planning {

/// The aircraft and payload a DJI camera is, as DJI WPML names them (swath/missions).
using DjiEnums = missions::DjiEnums;

/// A camera with a rectilinear lens, as its maker publishes it.
struct Camera {
  std::string name;
  double sensor_width_mm = 0.0;   ///< the sensor side along the image width, > 0
  double sensor_height_mm = 0.0;  ///< > 0
  double focal_length_mm = 0.0;   ///< > 0
  int image_width_px = 0;         ///< > 0
  int image_height_px = 0;        ///< > 0
  /// Shortest time between two photos the camera sustains, seconds (absent: no limit known).
  std::optional<double> min_trigger_interval_s;
  /// The DJI WPML enumerations for `swath plan --dji` (absent: not a camera DJI Pilot 2 flies).
  std::optional<DjiEnums> dji = std::nullopt;
};

/// Parses a camera YAML document:
///   name: Sony ILCE-QX1
///   sensor_width_mm: 23.2
///   sensor_height_mm: 15.4
///   focal_length_mm: 16
///   image_width_px: 5456
///   image_height_px: 3632
///   min_trigger_interval_s: 1.0   # optional
///   dji_drone_enum: 77            # optional, with dji_payload_enum (DjiEnums)
///   dji_drone_sub_enum: 0         # optional, default 0
///   dji_payload_enum: 66
/// Throws base::InputError naming `source`, the key and the problem (missing key, not a
/// number, value <= 0, unknown key).
Camera parse_camera(const std::string& yaml_text, const std::string& source);

/// One database entry: the name a user types (file stem) and the camera.
struct CameraEntry {
  std::string id;  ///< e.g. "sony-ilce-qx1"
  Camera camera;
};

/// Every camera in `directory` (*.yaml), sorted by id.
std::vector<CameraEntry> camera_database(const std::filesystem::path& directory);

/// `spec` is a path to a camera YAML file, or a database id, or a camera name (case-insensitive).
/// Throws InputError listing the closest ids when nothing matches.
Camera find_camera(const std::string& spec, const std::filesystem::path& database_directory);

}  // namespace swath::planning
