#pragma once
// The track an ArduPilot vehicle flies between two waypoints, in a local frame (LocalFrame).
//
// ArduPilot steers a leg as a straight line in its own frame: north and east offsets from its EKF
// origin (where it first had a position: home), scaled from degrees linearly, the east offset by
// the cosine of a latitude (Location::get_distance_NE: the mean of the point's and the origin's
// latitudes; ArduCopter before 4.1, the origin's). swath plans legs straight in a plane tangent
// to the ellipsoid. The two agree at the waypoints and part between them: by about
// L^2 tan(latitude) / (8 R) on an east-west leg of length L (2 cm for 1 km at 47 degrees, 8 m for
// 20 km, 44 m for 20 km at 80 degrees), more for legs far from the origin. swath plan writes a leg
// that strays more than planning's kMaxBow_m as several (mission.hpp); swath verify checks a zone
// or fence beside a leg against the straight leg (PX4 steers in a projection about its
// reference, near the tangent plane) and against ArduPilot's track under either conversion.
#include <array>
#include <vector>

#include "swath/geometry/local_frame.hpp"
#include "swath/geometry/point.hpp"

namespace swath::geometry {

class AutopilotTrack {
 public:
  /// `frame`: the local frame (kept by reference: it must outlive this); `home`: the origin, in
  /// it (metres east, north).
  AutopilotTrack(const LocalFrame& frame, Point2 home);

  /// How far the track of leg [a, b] (local metres) strays from the straight leg, metres: the
  /// larger of the two conversions' distances at the leg's middle, where a track bowed by the
  /// frames' curvature is farthest from its chord; near a pole (kNearPole_deg) the farthest of 63
  /// points along it. 0 for a leg of length 0.
  double bow_m(Point2 a, Point2 b) const;

  /// A cheap upper bound of bow_m(a, b), from the leg's length and how far it lies from the origin
  /// (no conversion): four times the bow of a track whose curvature is the greatest a parallel's
  /// has at the latitudes the leg may reach, plus the frames' own distortion that far out;
  /// +infinity near a pole (kNearPole_deg).
  double bow_bound_m(Point2 a, Point2 b) const;

  /// A bow below which a track is taken as its straight leg (a tenth of a millimetre: positions
  /// are written to 1e-9 degrees), and the pieces a track is drawn in: as many as keep its chords
  /// within that of it (at most 1024).
  static constexpr double kNegligibleBow_m = 1e-4;
  /// Beyond this latitude (the origin's, plus how far the leg lies from it) the track can bend
  /// most away from its middle (bow_m samples it all along) and bow_bound_m keeps no bound.
  static constexpr double kNearPole_deg = 85.0;
  static int pieces_for(double bow_m);

  /// The tracks of leg [a, b] under both conversions, each as `pieces` + 1 points from a to b
  /// (local metres; the chords between them stray from the track by about bow / pieces^2).
  std::array<std::vector<Point2>, 2> tracks(Point2 a, Point2 b, int pieces) const;

 private:
  /// Degrees north, degrees east scaled by the conversion's cosine (`model` 0: mean latitude,
  /// 1: the origin's), from the origin; and back to local metres.
  Point2 to_autopilot(Point2 local, int model) const;
  Point2 from_autopilot(Point2 offset, int model) const;
  /// How far the farther end of [a, b] lies from home, metres; the latitude a leg that far out
  /// may reach, degrees from the equator.
  double farthest_m(Point2 a, Point2 b) const;
  double reach_deg_of(double far_m) const;

  const LocalFrame& frame_;
  Point2 home_;
  GeoPoint origin_;
};

}  // namespace swath::geometry
