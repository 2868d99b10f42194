#include "swath/geometry/autopilot_track.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace swath::geometry {
namespace {

constexpr double kRadiansPerDegree = std::numbers::pi / 180;
constexpr double kEarthRadius_m = 6.35e6;  // the least radius of curvature, rounded down

// ArduPilot's longitude_scale(): the cosine of a latitude, kept at 0.01 or more near the poles.
double longitude_scale(double lat_deg) {
  return std::clamp(std::cos(lat_deg * kRadiansPerDegree), 0.01, 1.0);
}

// diff_longitude(): the difference taken the short way round the antimeridian.
double wrapped(double dlon_deg) {
  return dlon_deg - 360.0 * std::round(dlon_deg / 360.0);
}

}  // namespace

AutopilotTrack::AutopilotTrack(const LocalFrame& frame, Point2 home)
    : frame_(frame), home_(home), origin_(frame.to_geo(home)) {}

Point2 AutopilotTrack::to_autopilot(Point2 local, int model) const {
  const GeoPoint g = frame_.to_geo(local);
  const double scale =
      longitude_scale(model == 0 ? (g.lat_deg + origin_.lat_deg) / 2 : origin_.lat_deg);
  return {wrapped(g.lon_deg - origin_.lon_deg) * scale, g.lat_deg - origin_.lat_deg};
}

Point2 AutopilotTrack::from_autopilot(Point2 offset, int model) const {
  const double lat_deg = origin_.lat_deg + offset.y;
  const double scale =
      longitude_scale(model == 0 ? (lat_deg + origin_.lat_deg) / 2 : origin_.lat_deg);
  return frame_.to_local({lat_deg, wrapped(origin_.lon_deg + offset.x / scale), 0.0});
}

double AutopilotTrack::farthest_m(Point2 a, Point2 b) const {
  return std::max(distance(a, home_), distance(b, home_));
}

double AutopilotTrack::reach_deg_of(double far_m) const {
  return std::abs(origin_.lat_deg) + far_m / kEarthRadius_m / kRadiansPerDegree;
}

double AutopilotTrack::bow_bound_m(Point2 a, Point2 b) const {
  // A track's bow is about its curvature x L^2 / 8. A parallel at latitude phi curves by
  // tan(phi) / R in the tangent plane (ArduPilot's lines of constant north are parallels), and
  // the frames' scales part by about D / R at D from the origin, bending other lines by up to
  // that over R more; with 2 for the ellipsoid's flattening and the second conversion, and 4 on
  // the whole.
  const double length_m = distance(a, b);
  const double far_m = farthest_m(a, b);
  const double reach_deg = reach_deg_of(far_m);
  // Near a pole the track may bend most away from its middle, and no bound is kept: measured.
  if (reach_deg > kNearPole_deg) return std::numeric_limits<double>::infinity();
  const double curvature =
      2 * (std::tan(reach_deg * kRadiansPerDegree) + 1 + far_m / kEarthRadius_m) / kEarthRadius_m;
  return 4 * curvature * length_m * length_m / 8;
}

double AutopilotTrack::bow_m(Point2 a, Point2 b) const {
  if (a == b) return 0.0;
  const Point2 chord_middle = (a + b) * 0.5;
  const bool near_pole = reach_deg_of(farthest_m(a, b)) > kNearPole_deg;
  double bow = 0.0;
  for (const int model : {0, 1}) {
    const Point2 from = to_autopilot(a, model), to = to_autopilot(b, model);
    if (!near_pole) {  // a bow like a parabola's: farthest at the middle
      bow = std::max(bow, distance(from_autopilot((from + to) * 0.5, model), chord_middle));
      continue;
    }
    // Near a pole the track can bend most elsewhere (a meridian's turn): the farthest of 63
    // points along it from the chord.
    for (int k = 1; k < 64; ++k) {
      const Point2 p = from_autopilot(from + (to - from) * (k / 64.0), model);
      const Point2 d = b - a;
      const double t = std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0);
      bow = std::max(bow, distance(p, a + d * t));
    }
  }
  return bow;
}

int AutopilotTrack::pieces_for(double bow_m) {
  return static_cast<int>(std::clamp(std::ceil(std::sqrt(bow_m / kNegligibleBow_m)), 1.0, 1024.0));
}

std::array<std::vector<Point2>, 2> AutopilotTrack::tracks(Point2 a, Point2 b, int pieces) const {
  std::array<std::vector<Point2>, 2> out;
  for (const int model : {0, 1}) {
    const Point2 from = to_autopilot(a, model), to = to_autopilot(b, model);
    std::vector<Point2>& track = out[static_cast<std::size_t>(model)];
    track.push_back(a);
    for (int k = 1; k < pieces; ++k)
      track.push_back(
          from_autopilot(from + (to - from) * (static_cast<double>(k) / pieces), model));
    track.push_back(b);
  }
  return out;
}

}  // namespace swath::geometry
