#pragma once

#include <GeographicLib/LocalCartesian.hpp>

#include <optional>
#include <vector>

#include "swath/geometry/point.hpp"

namespace swath::geometry {

/// A local east-north-up frame in metres tangent to the WGS84 ellipsoid at `origin`
/// (GeographicLib::LocalCartesian). A ground point (altitude 0) maps to the (east, north)
/// coordinates of its position on the ellipsoid, and back exactly: to_geo() finds the ellipsoid
/// point with those (east, north) coordinates. Round trip error < 1e-6 m within 20 km of the
/// origin (tests check 1 mm at 20 km). Distances and areas in the frame differ from geodesic ones
/// by less than 1e-5 relative within 20 km.
class LocalFrame {
 public:
  explicit LocalFrame(GeoPoint origin);

  const GeoPoint& origin() const { return origin_; }
  /// Local (east, north) metres of a WGS84 point; its altitude is ignored.
  Point2 to_local(const GeoPoint& p) const;
  /// WGS84 point on the ellipsoid (altitude `alt_m`) whose local coordinates are `p`.
  GeoPoint to_geo(Point2 p, double alt_m = 0.0) const;

 private:
  GeoPoint origin_;
  GeographicLib::LocalCartesian frame_;
};

/// Geodesic distance on the WGS84 ellipsoid between two points (altitudes ignored), metres;
/// accurate to nanometres at any distance (GeographicLib::Geodesic, Karney 2013).
double geodesic_distance_m(const GeoPoint& a, const GeoPoint& b);

/// How far an edge straight in longitude and latitude (RFC 7946's reading of an area file, and
/// the one ArduPilot and PX4 test fences by) may stray from the frame's straight chord between
/// its ends before points are inserted along it: 1 cm, the precision swath writes positions at
/// (7 decimals of a degree, 1.1 cm) and far below any GNSS fix. A 1 km east-west edge at 47° N
/// strays 2 cm, at 65° N 4 cm; fields' edges (tens to hundreds of metres) stray under a millimetre.
inline constexpr double kEdgeDepartureTolerance_m = 0.01;

/// How far swath plan reads a hole's or no-fly zone's edge off its lon/lat line (the plan follows
/// an edge that bows more within this), and so the slack the preflight check allows a zone where
/// its edges bow: 5 cm. At 1 cm the random-layout safety test's 1.2 km zones, bowing 1-2 cm,
/// left plans a few millimetres short of the clearance from the zone as drawn.
inline constexpr double kZoneEdgeDepartureTolerance_m = 0.05;

/// `ring` (closed by its last vertex's edge back to the first) with points inserted along each
/// edge's line straight in longitude and latitude, wherever that line strays from the frame's
/// straight chord by more than `tolerance_m`, so that the ring's chords in the frame follow the
/// shape as drawn. `from_vertex`, if given, receives for each output point the index of the
/// input vertex whose edge it lies on. Short edges are kept as they are.
std::vector<GeoPoint> densify_lonlat_edges(const LocalFrame& frame,
                                           const std::vector<GeoPoint>& ring,
                                           std::vector<std::size_t>* from_vertex = nullptr,
                                           double tolerance_m = kEdgeDepartureTolerance_m);

/// The most any edge of `ring` (closed as above), straight in longitude and latitude, strays
/// from the frame's chord between its ends, metres.
double largest_lonlat_departure_m(const LocalFrame& frame, const std::vector<GeoPoint>& ring);

/// The reverse, for a ring swath writes (a fence): `ring` in the frame (closed as above) with
/// points inserted along each chord wherever the line straight in longitude and latitude between
/// its ends' positions strays from it by more than `tolerance_m`, so that an autopilot's
/// lon/lat-straight edges follow the ring swath planned in.
std::vector<Point2> densify_local_edges(const LocalFrame& frame, const std::vector<Point2>& ring,
                                        double tolerance_m = kEdgeDepartureTolerance_m);

/// An edge of a ring whose longitudes, as written, differ by 180 degrees or more: ArduPilot
/// (AC_PolyFence_loader::breached, Polygon_outside on the stored int32 latitude and longitude)
/// and PX4 (Geofence::insidePolygon) test a fence's edges in raw longitude, without wrapping, so
/// such an edge runs the long way round the globe and the fence is not the shape meant (a field
/// across the ±180° meridian becomes the rest of its latitude band). Longitudes beyond ±180 are
/// no way out: ArduPilot refuses them (check_lng). One ±180 wrap of each longitude first.
struct AntimeridianEdge {
  std::size_t from = 0;  ///< the edge from vertex `from` to the next (the first after the last)
  GeoPoint a, b;         ///< its ends, longitudes in [-180, 180]
};
std::optional<AntimeridianEdge> edge_across_antimeridian(const std::vector<GeoPoint>& ring);

}  // namespace swath::geometry
