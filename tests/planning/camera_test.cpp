#include "swath/planning/camera.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "swath/base/input_error.hpp"
#include "swath/planning/imaging.hpp"

namespace swath::planning {
namespace {

const std::string kDatabase = std::string(SWATH_SOURCE_DIR) + "/share/cameras";

std::string error_of(const std::string& yaml) {
  try {
    parse_camera(yaml, "cam.yaml");
  } catch (const base::InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(CameraFile, ParsesEveryKey) {
  const Camera c = parse_camera(
      "name: Test cam\nsensor_width_mm: 13.2\nsensor_height_mm: 8.8\nfocal_length_mm: 8.8\n"
      "image_width_px: 5472\nimage_height_px: 3648\nmin_trigger_interval_s: 2\n",
      "t");
  EXPECT_EQ(c.name, "Test cam");
  EXPECT_DOUBLE_EQ(c.sensor_width_mm, 13.2);
  EXPECT_EQ(c.image_height_px, 3648);
  EXPECT_DOUBLE_EQ(*c.min_trigger_interval_s, 2.0);
}

TEST(CameraFile, BadFilesNameKeyAndLine) {
  const std::string base =
      "name: x\nsensor_width_mm: 10\nsensor_height_mm: 8\nimage_width_px: 100\nimage_height_px: "
      "80\n";
  EXPECT_NE(error_of(base).find("cam.yaml: the camera has no focal_length_mm"), std::string::npos);
  EXPECT_NE(error_of(base + "focal_length_mm: 0\n")
                .find("line 6: focal_length_mm 0 mm is outside the range swath accepts, 1 to 2000"),
            std::string::npos);
  // The overflowing camera of issue 16: refused at the key, before any footprint is computed.
  EXPECT_NE(error_of(base + "focal_length_mm: 1e-300\n").find("focal_length_mm 1e-300 mm"),
            std::string::npos);
  EXPECT_NE(
      error_of(base + "focal_length_mm: abc\n").find("line 6: focal_length_mm must be a number"),
      std::string::npos);
  EXPECT_NE(error_of(base + "focal_length_mm: 5\nzoom: 3\n").find("line 7: unknown key 'zoom'"),
            std::string::npos);
  EXPECT_NE(error_of("name: [unclosed\n").find("invalid YAML"), std::string::npos);
  EXPECT_NE(error_of("- a list\n").find("mapping"), std::string::npos);
}

TEST(CameraFile, DjiEnumsAreOptionalWholeNumbersThatGoTogether) {
  const std::string base =
      "name: x\nsensor_width_mm: 10\nsensor_height_mm: 8\nfocal_length_mm: 5\n"
      "image_width_px: 100\nimage_height_px: 80\n";
  EXPECT_FALSE(parse_camera(base, "t").dji);
  const Camera c =
      parse_camera(base + "dji_drone_enum: 67\ndji_drone_sub_enum: 1\ndji_payload_enum: 53\n", "t");
  ASSERT_TRUE(c.dji);
  EXPECT_EQ(c.dji->drone, 67);
  EXPECT_EQ(c.dji->drone_sub, 1);
  EXPECT_EQ(c.dji->payload, 53);
  EXPECT_EQ(parse_camera(base + "dji_drone_enum: 77\ndji_payload_enum: 66\n", "t").dji->drone_sub,
            0);
  EXPECT_NE(error_of(base + "dji_drone_enum: 77\n").find("go together"), std::string::npos);
  EXPECT_NE(error_of(base + "dji_drone_sub_enum: 1\n").find("needs dji_drone_enum"),
            std::string::npos);
  EXPECT_NE(error_of(base + "dji_drone_enum: 77.5\ndji_payload_enum: 66\n")
                .find("line 7: dji_drone_enum must be a whole number"),
            std::string::npos);
  EXPECT_NE(error_of(base + "dji_drone_enum: 70000\ndji_payload_enum: 66\n")
                .find("outside the range swath accepts, 0 to 65535"),
            std::string::npos);
  // The bundled DJI cameras Pilot 2 flies carry their enums (DJI Cloud API's product table).
  const Camera m3e = find_camera("dji-mavic-3e", kDatabase);
  ASSERT_TRUE(m3e.dji);
  EXPECT_EQ(m3e.dji->drone, 77);
  EXPECT_EQ(m3e.dji->payload, 66);
  EXPECT_FALSE(find_camera("sony-ilce-qx1", kDatabase).dji);
}

TEST(CameraDatabase, HoldsAtLeastTwelveValidRealCameras) {
  const auto entries = camera_database(kDatabase);
  ASSERT_GE(entries.size(), 12u);
  for (const CameraEntry& e : entries) {
    EXPECT_NO_THROW(validate_camera(e.camera, e.id));
    // Pixel pitch of real sensors: 1 to 20 µm, nearly square.
    const double pitch_w = e.camera.sensor_width_mm / e.camera.image_width_px * 1000;
    const double pitch_h = e.camera.sensor_height_mm / e.camera.image_height_px * 1000;
    EXPECT_GT(pitch_w, 1.0) << e.id;
    EXPECT_LT(pitch_w, 20.0) << e.id;
    EXPECT_NEAR(pitch_w / pitch_h, 1.0, 0.05) << e.id;
  }
}

TEST(CameraDatabase, FindsByIdNameOrFileAndSuggestsOtherwise) {
  EXPECT_EQ(find_camera("sony-ilce-qx1", kDatabase).image_width_px, 5456);
  EXPECT_EQ(find_camera("sony ilce-qx1", kDatabase).focal_length_mm, 16.0);
  EXPECT_EQ(find_camera(kDatabase + "/dji-phantom-4-pro.yaml", kDatabase).sensor_width_mm, 13.2);
  try {
    find_camera("sony-a9", kDatabase);
    ADD_FAILURE();
  } catch (const base::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean sony-"), std::string::npos) << e.what();
  }
}

// find_camera() reads an id's own file only; every bundled id must give the camera the whole
// database holds for it, field by field.
TEST(CameraDatabase, AnIdGivesTheDatabasesCamera) {
  for (const CameraEntry& e : camera_database(kDatabase)) {
    const Camera c = find_camera(e.id, kDatabase);
    EXPECT_EQ(c.name, e.camera.name) << e.id;
    EXPECT_EQ(c.sensor_width_mm, e.camera.sensor_width_mm) << e.id;
    EXPECT_EQ(c.sensor_height_mm, e.camera.sensor_height_mm) << e.id;
    EXPECT_EQ(c.focal_length_mm, e.camera.focal_length_mm) << e.id;
    EXPECT_EQ(c.image_width_px, e.camera.image_width_px) << e.id;
    EXPECT_EQ(c.image_height_px, e.camera.image_height_px) << e.id;
    EXPECT_EQ(c.min_trigger_interval_s, e.camera.min_trigger_interval_s) << e.id;
    EXPECT_EQ(c.dji.has_value(), e.camera.dji.has_value()) << e.id;
  }
}

// An id is found by its file alone: another, broken file in the folder does not stop it, while a
// name (which needs every file) still reports the broken one.
TEST(CameraDatabase, AnIdIsReadFromItsOwnFileOnly) {
  const std::filesystem::path dir =
      std::filesystem::path(testing::TempDir()) / "swath-camera-by-id";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(kDatabase + "/sony-ilce-qx1.yaml", dir / "sony-ilce-qx1.yaml");
  std::ofstream(dir / "broken.yaml") << "name: Broken\nsensor_width_mm: -1\n";
  EXPECT_EQ(find_camera("Sony-ILCE-QX1", dir).image_width_px, 5456);
  try {
    find_camera("Sony ILCE-QX1", dir);
    ADD_FAILURE();
  } catch (const base::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.yaml"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace swath::planning
