#pragma once
// swath-fleet's safety envelope (docs/swath-fleet.md, "Safety envelope"): a ceiling above home,
// the least 3-D separation between airborne drones, and a geofence of inclusion and exclusion
// polygons with a height limit. The fleet file gives it (ceiling_m, separation_m, fence; read by
// vehicle::parse_fleet_file, the one fleet-file reader); the runtime keeps every drone inside it
// and `swath-fleet check` judges a log against it.
//
//   ceiling_m: 120        # m above home; the top drone's layer must fit under it
//   separation_m: 5       # m; layers and default homes are spaced at least this
//   fence:
//     geojson: field.geojson   # Polygon / MultiPolygon features, lat/lon degrees (WGS84);
//                              # properties.fence: inclusion (default) or exclusion
//     max_altitude_m: 100      # m above home; optional, else the ceiling

#include <array>
#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "swath/geometry/point.hpp"
#include "swath/geometry/visibility.hpp"
#include "swath/vehicle/fleet_file.hpp"
#include "swath/vehicle/vec3.hpp"

namespace swath::fleet {

/// One fence polygon as the fleet file's reader gives it (WGS84 degrees, not closed).
using vehicle::FencePolygon;
/// A fence file's polygons (read by the fleet file's reader; here for the fence's other users).
using vehicle::parse_fence_geojson;

/// The geofence as a value a MAVLink backend can upload (inclusion and exclusion polygons,
/// mission_type FENCE) and the runtime checks every target against.
struct Fence {
  std::vector<FencePolygon> polygons;
  double max_altitude_m = std::numeric_limits<double>::infinity();  ///< above home, m
};

/// The envelope as the fleet file gives it.
struct Envelope {
  double ceiling_m = 120;   ///< above home, m (0, 10000]
  double separation_m = 5;  ///< least 3-D distance between airborne drones, m (0, 1000]
  Fence fence;
};

/// The envelope in a world's local metres (x east, y north, z above home): what the runtime and
/// the checker test positions against.
struct LocalEnvelope {
  double ceiling_m = 120;
  double separation_m = 5;
  double fence_max_altitude_m = std::numeric_limits<double>::infinity();
  std::vector<std::vector<std::array<double, 2>>> inclusions, exclusions;  ///< rings, local m
  /// "" when a drone may be at `p` (z: above home, m); else why not, one phrase ("above the
  /// ceiling of 120 m", "outside the inclusion fence", "inside an exclusion fence").
  std::string refusal(const vehicle::Vec3& p) const;
  /// The same for the horizontal position alone (homes, fly_to targets before their height).
  std::string refusal_xy(double x_m, double y_m) const;
  /// Whether it has any fence polygon (else every place at the right height is inside).
  bool fenced() const { return !inclusions.empty() || !exclusions.empty(); }
  /// "" when the straight horizontal leg a-b stays inside the fence, else why not ("outside the
  /// inclusion fence", "inside an exclusion fence" somewhere along it).
  std::string leg_refusal(const vehicle::Vec3& a, const vehicle::Vec3& b) const;
  /// "" when the triangle a-b-c lies inside the fence: its sides stay inside and no exclusion
  /// lies within it. A drone flying a to b with home c is then inside whenever it turns straight
  /// home on the way (the runtime flies straight legs).
  std::string triangle_refusal(const vehicle::Vec3& a, const vehicle::Vec3& b,
                               const vehicle::Vec3& c) const;
  /// The stops of the way from a to b inside the fence, b last (the bends at b's height): b alone
  /// when the straight leg stays inside; else, once build_routes() has run, the shortest path
  /// inside the fence and out of the exclusions (geometry::VisibilityRouter, its bends
  /// kRouteCornerAllowance_m off the corners), every leg of it checked by leg_refusal(). Empty
  /// when there is no such way.
  std::vector<vehicle::Vec3> route(const vehicle::Vec3& a, const vehicle::Vec3& b) const;
  /// Lets route() bend round the fence (the runtime does it when its vehicles can follow a bent
  /// way home: the simulated fleet).
  void build_routes();
  /// Whether a drone at `a` with home `home` may be given target b: with routes, a way there and a
  /// way home from it inside the fence (from anywhere on the way, which stays inside, the way home
  /// is routed as well); without, the triangle a-b-home inside it (straight ways home).
  bool reachable(const vehicle::Vec3& a, const vehicle::Vec3& b, const vehicle::Vec3& home) const;
  bool routes() const { return router != nullptr; }
  /// Shared by the envelope's copies; its tables fill as it answers (one thread at a time).
  std::shared_ptr<const geometry::VisibilityRouter> router;
};

/// How far a route's bend keeps off its fence corner, m: an autopilot cuts a bend (ArduCopter by
/// up to ~1.7 m in SITL), as swath plan's lanes allow.
inline constexpr double kRouteCornerAllowance_m = 2.0;

/// `fence` in the local frame at `origin`.
LocalEnvelope local_envelope(const Envelope& e, const geometry::GeoPoint& origin);

/// The envelope a fleet file gives (vehicle::parse_fleet_file read its ceiling_m, separation_m
/// and fence), the defaults for what it does not give.
Envelope envelope_of(const vehicle::FleetFile& file);

/// The altitude layers (drone i at base_m + step_m × i) of `drones` drones under the lower of
/// `ceiling_m` and the fence's `fence_height_m`: "" when they fit, else one sentence naming the
/// limit and what would lift it (lowering separation_m only where it sets the step:
/// `separation_sets_step`).
std::string layers_refusal(int drones, double base_m, double step_m, double ceiling_m,
                           double fence_height_m, bool separation_sets_step);

/// The most vertices a run's fence may have, its inclusions and exclusions together: the log's
/// run_start carries them, and a line of events.jsonl is at most 1 MiB (`check`, `render`).
inline constexpr std::size_t kMaxFenceVertices = 20000;

/// "" when `e`'s rings have at most kMaxFenceVertices vertices, else one sentence saying so.
std::string fence_size_refusal(const LocalEnvelope& e);

}  // namespace swath::fleet
