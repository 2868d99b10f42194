#pragma once
// Vehicle and environment files of docs/swath-control.md (share/vehicles/*.yaml,
// share/environments/*.yaml): units in every key name (speeds in _m_s; the old _mps spellings
// read with a warning), unknown keys refused naming file, line and key, numbers outside their
// range refused. A vehicle file's control sections (estimator, controller, computer) and its
// battery are named here and read by the programs that use them (control/, energy's Battery).

#include <string>
#include <vector>

#include "swath/vehicle/multirotor.hpp"
#include "swath/vehicle/sensors.hpp"
#include "swath/vehicle/wind.hpp"

namespace swath::vehicle {

/// What flies, as a vehicle file describes it.
struct VehiclePhysics {
  Airframe airframe;
  EscSettings esc;
  std::vector<SensorSettings> sensors;  ///< in file order (their events run in this order)
  double avionics_w = 3.0;              ///< GPS, radio, receiver: drawn all the time
  std::vector<std::string> warnings;    ///< old key spellings
};

/// The defaults (docs/swath-control.md, 'Vehicle, scheduler and environment files'): a quad-f450
/// with gyro, accel, mag, baro and GPS.
VehiclePhysics default_vehicle();
/// The default sensors (gyro and accel at 1 kHz, mag 100 Hz, baro 50 Hz, GPS 10 Hz).
std::vector<SensorSettings> default_sensors();

/// Parses a vehicle file's physical sections: name, frame, rotors (layout or list), propeller,
/// motor, esc, sensors, avionics_w; every key optional (the defaults above). Throws
/// base::InputError naming `source`, the line and the key.
VehiclePhysics parse_vehicle(const std::string& yaml_text, const std::string& source);

/// The environment: wind parts and the air.
struct Environment {
  std::string name = "calm";
  MeanWind mean_wind;
  bool dryden = false;
  double w20_m_s = 0.0;              ///< Dryden's W20 (wind at 20 ft)
  double reference_speed_m_s = 0.0;  ///< V of the frozen field; 0: max(mean wind, speed, 1)
  double update_hz = 200.0;          ///< turbulence samples per second
  GustSettings gusts;
  std::vector<WindRegion> regions;
  double air_density_kg_m3 = 1.225;
  double gravity_m_s2 = kStandardGravity_m_s2;
  std::vector<std::string> warnings;
};

/// The presets calm, lab, rugby and arch (docs/swath-control.md, 'Vehicle, scheduler and
/// environment files'); throws InputError for another name.
Environment environment_preset(const std::string& name);
/// Parses an environment file (keys as the environments of docs/swath-control.md, 'Vehicle,
/// scheduler and environment files'; `preset:` starts from one).
Environment parse_environment(const std::string& yaml_text, const std::string& source);

}  // namespace swath::vehicle
