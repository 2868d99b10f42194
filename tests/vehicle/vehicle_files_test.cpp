// The bundled vehicle and environment files read back as docs/swath-control.md, 'Vehicle, scheduler
// and environment files' says, the presets agree with their files, and bad files are refused naming
// the file, the line and the key.
#include "swath/vehicle/vehicle_files.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "swath/base/input_error.hpp"

namespace swath::vehicle {
namespace {

std::string share(const std::string& path) {
  std::ifstream f(std::string(SWATH_SOURCE_DIR) + "/share/" + path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string error_of(const std::string& text) {
  try {
    parse_vehicle(text, "v.yaml");
  } catch (const base::InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(VehicleFiles, TheBundledVehiclesHoverAsDesignSays) {
  const VehiclePhysics quad = parse_vehicle(share("vehicles/quad-f450.yaml"), "quad-f450.yaml");
  EXPECT_NEAR(hover(quad.airframe).rotor_rad_s[0], 678.0, 0.05);
  EXPECT_NEAR(hover(quad.airframe).motor_power_w, 195.3, 0.05);
  ASSERT_EQ(quad.sensors.size(), 5u);
  EXPECT_EQ(quad.sensors[0].period_ns, 1'000'000);
  EXPECT_EQ(quad.sensors[4].type, SensorType::position);
  EXPECT_DOUBLE_EQ(quad.sensors[4].latency_s, 0.1);
  EXPECT_TRUE(quad.warnings.empty());
  // The file states the defaults: the same as default_vehicle().
  const VehiclePhysics d = default_vehicle();
  EXPECT_EQ(hover(d.airframe).rotor_rad_s[0], hover(quad.airframe).rotor_rad_s[0]);
  EXPECT_EQ(d.sensors.size(), quad.sensors.size());
  for (std::size_t i = 0; i < d.sensors.size(); ++i) {
    EXPECT_EQ(d.sensors[i].period_ns, quad.sensors[i].period_ns) << i;
    EXPECT_EQ(d.sensors[i].noise, quad.sensors[i].noise) << i;
    EXPECT_EQ(d.sensors[i].lsb, quad.sensors[i].lsb) << i;
  }
  const VehiclePhysics hexa = parse_vehicle(share("vehicles/hexa-f550.yaml"), "hexa-f550.yaml");
  EXPECT_EQ(hexa.airframe.rotors.size(), 6u);
  EXPECT_NEAR(hover(hexa.airframe).rotor_rad_s[0], 700.2, 0.05);
  EXPECT_NEAR(hover(hexa.airframe).motor_power_w, 322, 0.5);
  const VehiclePhysics y6 = parse_vehicle(share("vehicles/y6.yaml"), "y6.yaml");
  ASSERT_EQ(y6.airframe.rotors.size(), 6u);
  EXPECT_EQ(y6.airframe.rotors[1].efficiency, 0.8);
  EXPECT_NO_THROW(parse_vehicle(share("vehicles/quad-f450-cc3d.yaml"), "cc3d.yaml"));
}

TEST(VehicleFiles, BadVehiclesAreNamed) {
  EXPECT_EQ(error_of("frame: {mass_kg: 0}\n"),
            "v.yaml: line 1: frame.mass_kg must be in (0.0000, 1000.0000], found 0");
  EXPECT_NE(error_of("frame: {wingspan_m: 2}\n").find("unknown key 'frame.wingspan_m'"),
            std::string::npos);
  EXPECT_NE(error_of("rotors: {layout: octo}\n").find("must be quad_x, hexa_x or y6"),
            std::string::npos);
  EXPECT_NE(error_of("sensors:\n  - {type: gyro, rate_hz: 3000}\n").find("whole nanoseconds"),
            std::string::npos);
  EXPECT_NE(error_of("sensors:\n  - {type: gyro}\n").find("give one of rate_hz and period_us"),
            std::string::npos);
  EXPECT_NE(error_of("esc: {pwm_min_us: 2000, pwm_max_us: 1000}\n").find("greater than"),
            std::string::npos);
  EXPECT_NE(error_of("rotors:\n  - {spin: cw}\n").find("needs position_m"), std::string::npos);
  // A rotor list: where the rotors are, read as given.
  const VehiclePhysics tri = parse_vehicle(
      "rotors:\n  - {position_m: [0.2, 0, 0], spin: ccw}\n  - {position_m: [-0.1, 0.17, 0], "
      "spin: cw}\n  - {position_m: [-0.1, -0.17, 0], spin: ccw, efficiency: 0.9}\n",
      "tri.yaml");
  ASSERT_EQ(tri.airframe.rotors.size(), 3u);
  EXPECT_EQ(tri.airframe.rotors[1].spin, -1);
  EXPECT_EQ(tri.airframe.rotors[2].efficiency, 0.9);
  // Control sections and the battery are named, not read, here.
  EXPECT_EQ(error_of("controller: {position_p: 1}\nbattery: {capacity_ah: 5}\n"), "accepted");
}

TEST(EnvironmentFiles, TheFilesAreThePresets) {
  for (const char* name : {"calm", "lab", "rugby", "arch"}) {
    const Environment file =
        parse_environment(share(std::string("environments/") + name + ".yaml"), name);
    const Environment preset = environment_preset(name);
    EXPECT_EQ(file.name, name);
    EXPECT_EQ(file.mean_wind.speed_m_s, preset.mean_wind.speed_m_s) << name;
    EXPECT_EQ(file.mean_wind.from_deg, preset.mean_wind.from_deg) << name;
    EXPECT_EQ(file.mean_wind.ramp_m_s_per_min, preset.mean_wind.ramp_m_s_per_min) << name;
    EXPECT_EQ(file.dryden, preset.dryden) << name;
    EXPECT_EQ(file.w20_m_s, preset.w20_m_s) << name;
    EXPECT_EQ(file.gusts.rate_per_min, preset.gusts.rate_per_min) << name;
    EXPECT_EQ(file.gusts.amplitude_m_s, preset.gusts.amplitude_m_s) << name;
    EXPECT_EQ(file.regions.size(), preset.regions.size()) << name;
  }
  EXPECT_THROW(environment_preset("storm"), base::InputError);
  try {
    parse_environment("mean_wind: {speed_mps: 3, gust: 1}\n", "e.yaml");
    ADD_FAILURE();
  } catch (const base::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown key 'mean_wind.gust'"), std::string::npos);
  }
  const Environment old = parse_environment("mean_wind: {speed_mps: 3}\n", "e.yaml");
  EXPECT_EQ(old.mean_wind.speed_m_s, 3);
  EXPECT_EQ(old.warnings.size(), 1u);
}

}  // namespace
}  // namespace swath::vehicle
