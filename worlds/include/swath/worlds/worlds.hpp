#pragma once
// The worlds of swath-fleet's case studies (paper 000 §5.1–5.2; docs/swath-fleet.md) and their
// world files: what the applications act in (the apps themselves are fleet/apps/,
// swath/fleet/apps.hpp). Every sensor's noise is a hash of (seed, sensor, position to the
// millimetre), not of time or order, so a reading does not depend on the schedule
// (docs/swath-fleet.md): two schedulers sensing the same place see the same value, and a case's
// oracle is exact.
//
// World YAML (local metres at `origin`, x east, y north):
//   kind: hotspot            # hotspot | road | sites
//   origin: {lat: 42.3601, lon: -71.0942}
//   seed: 7
//   fence: {width_m: 200, height_m: 200}     # centred on the origin; optional
//   ... the kind's own keys (see each struct below)

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "swath/fleet/runtime.hpp"
#include "swath/fleet/world.hpp"
#include "swath/geometry/point.hpp"

namespace swath::worlds {

using fleet::Vec3;

/// A sensor: how long a reading takes and its noise.
struct SensorSpec {
  std::string name;
  double time_s = 2.0;   ///< > 0
  double noise = 1.0;    ///< standard deviation in the sensor's unit (dB, m), ≥ 0
  double noise_deg = 0;  ///< road_camera: heading noise, degrees, ≥ 0
};

/// The parts every world has.
class BaseWorld : public fleet::World {
 public:
  std::string kind() const override { return kind_; }
  Vec3 start() const override { return start_; }
  std::vector<std::array<double, 2>> fence() const override { return fence_; }
  double sense_time_s(const std::string& sensor) const override;

  std::string kind_;
  geometry::GeoPoint origin;
  bool has_origin = false;  ///< the world file gives its origin (else local metres only)
  std::uint64_t seed = 1;
  Vec3 start_;
  std::vector<std::array<double, 2>> fence_;
  std::vector<SensorSpec> sensors;
  const SensorSpec& sensor(const std::string& name) const;  ///< throws ActionFailed
  /// N(0, 1) from (seed, sensor, x, y): the same at the same place whatever the schedule.
  double place_noise(const std::string& sensor, double x_m, double y_m) const;
};

/// Case 3 (paper 000 §5.1.3): a signal source; `signal` reads p0 − 10 n log10(max(d, 1 m)) + noise,
/// dBm. App `hotspot`: sense at the corners of a square of side `side_m` around the current place,
/// move `step_m` toward the strongest corner, `steps` times.
class HotspotWorld final : public BaseWorld {
 public:
  fleet::Reading sense(const std::string& sensor, const Vec3& at, double t_s) const override;
  Vec3 source_m;          ///< default: 60 m from the start at a bearing drawn from the seed
  double p0_dbm = -30;    ///< at 1 m
  double exponent = 2.0;  ///< path-loss exponent, > 0
  int steps = 10;
  double side_m = 10, step_m = 5;
};

/// Case 1 (paper 000 §5.1.1): a road (a polyline, or a smooth random curve from the seed);
/// `road_camera` reads the nearest road point and the road's heading there (x_m, y_m, heading_deg
/// clockwise from north), with noise. App `road`: fly to a point, read, step `step_m` along the
/// road, `steps` times.
class RoadWorld final : public BaseWorld {
 public:
  fleet::Reading sense(const std::string& sensor, const Vec3& at, double t_s) const override;
  std::vector<std::array<double, 2>> road_m;  ///< ≥ 2 points
  int steps = 25;
  double step_m = 6;
  /// The nearest point of the road to (x, y) and the road's heading there (radians from +x, ccw).
  std::array<double, 3> nearest(double x_m, double y_m) const;
};

/// Case 4 (paper 000 §5.2.1): named sites. App `multiplexing`: a delivery A→F (same drone;
/// interruptible unless `delivery_interruptible` is false, the paper's baseline), photos at B and
/// E, a video from C to D (same drone, not interruptible); `camera` takes a photo.
class SitesWorld final : public BaseWorld {
 public:
  fleet::Reading sense(const std::string& sensor, const Vec3& at, double t_s) const override;
  std::vector<std::pair<std::string, Vec3>> sites;  ///< A..F; B–E drawn in `area_m` when absent
  double handling_s = 5;                            ///< pick-up and drop, s
  bool delivery_interruptible = true;
  Vec3 site(const std::string& name) const;
};

/// Case 2 (paper 000 §5.1.2): a Wi-Fi field: access points with log-distance path loss and a
/// shadowing field correlated over `correlation_m` (random Fourier features of an RBF kernel:
/// smooth, from the seed); `rssi` reads the strongest AP plus noise, dBm. App `wifi`: one sensing
/// task per cell of a `cell_m` grid over the fence; each reading updates a Gaussian process (RBF
/// length `gp_length_m`, σ_f `gp_sigma_f`, σ_n `gp_sigma_n_db`) and cancels every cell whose
/// posterior standard deviation fell below `cancel_below_db` (Fig. 8's cancellation).
class RfFieldWorld final : public BaseWorld {
 public:
  fleet::Reading sense(const std::string& sensor, const Vec3& at, double t_s) const override;
  struct AccessPoint {
    double x_m, y_m, p0_dbm, exponent;
  };
  std::vector<AccessPoint> access_points;
  double shadowing_db = 4, correlation_m = 15;
  double cell_m = 5, gp_length_m = 12, gp_sigma_f = 6, gp_sigma_n_db = 2, cancel_below_db = 3;
  double width_m = 50, height_m = 70;
  /// The noiseless signal at (x, y), dBm (the map's truth).
  double truth_dbm(double x_m, double y_m) const;
  std::vector<std::array<double, 3>> features;  ///< (wx, wy, phase) of the shadowing field
};

/// Case 5 (paper 000 §5.2.2): a walker at `walker_speed_m_s` along a smooth random path within
/// `area_radius_m` of the start; `camera` sees it
/// within `camera_range_m` (values: its x_m, y_m; empty when out of sight). App `tracking`: fly
/// to where it was last seen, look, repeat, for `duration_s`; drones with short flights hand
/// over (the fleet file's max_flight_time_s and recharge_s).
class TrackingWorld final : public BaseWorld {
 public:
  fleet::Reading sense(const std::string& sensor, const Vec3& at, double t_s) const override;
  double walker_speed_m_s = 1.4, camera_range_m = 15, duration_s = 300;
  double area_radius_m = 60;  ///< beyond this distance from the start it turns back
  /// Where the walker is at `t_s`.
  std::array<double, 2> walker_at(double t_s) const;
  double heading0 = 0;
  std::array<double, 3> turn_amp{}, turn_freq{}, turn_phase{};
};

/// Static work from a file (docs/swath-fleet.md: declarative files only for work that does not
/// depend on readings). App `static`: each task starts once the tasks it comes `after` are done,
/// queues its actions and ends with the last. World file:
///   kind: static
///   sensors: {camera: {time_s: 2}}
///   tasks:
///     - name: north-photo
///       kind: photo                 # the logic task (default: the name)
///       same_drone: false           # binding flags (docs/swath-fleet.md)
///       interruptible: true
///       after: [pickup]             # names of tasks that must be done first
///       actions:
///         - fly_to: {x_m: 10, y_m: 40, alt_m: 0}   # alt_m 0: the drone's altitude layer
///         - sense: camera
///         - hover: 5                # seconds
///         - custom: {name: drop, s: 3}
/// Names are unique; `after` names earlier or later tasks but no cycle; `sense` names a sensor of
/// the file (any name gets a 2 s default sensor when `sensors` does not list it).
class StaticWorld final : public BaseWorld {
 public:
  fleet::Reading sense(const std::string& sensor, const Vec3& at, double t_s) const override;
  struct Step {
    int type = 0;  ///< 0 fly_to, 1 sense, 2 hover, 3 custom (fleet::Ctx's actions)
    Vec3 to;
    std::string name;
    double seconds = 0;
  };
  struct Task {
    std::string name, kind;
    fleet::Flags flags;
    std::vector<std::size_t> after;  ///< indices into tasks
    std::vector<Step> steps;
  };
  std::vector<Task> tasks;
};

/// Reads a world file. Throws base::InputError naming `source`, the line and the key.
/// `seed`: instead of the file's seed (a scenario of the same world; swath-fleet compare).
std::unique_ptr<BaseWorld> parse_world(const std::string& text, const std::string& source,
                                       std::optional<std::uint64_t> seed = {});
std::unique_ptr<BaseWorld> read_world(const std::string& path);

/// The world kinds: hotspot, road, rf_field, sites, static, tracking.
const std::vector<std::string>& world_kinds();

}  // namespace swath::worlds
