#pragma once
// The per-file checks behind verify() (issue 45), in the check's common local frame.

#include <limits>
#include <string>
#include <vector>

#include "swath/geometry/polygon.hpp"
#include "swath/preflight/verify.hpp"

namespace swath::preflight {

/// The least distance between a segment and something, and the point of the segment it is at.
struct SegmentDistance {
  double distance_m = 0.0;
  geometry::Point2 at;
};

/// Between the segments [p, q] and [a, b] (0 where they meet, exactly decided).
SegmentDistance segment_distance(geometry::Point2 p, geometry::Point2 q, geometry::Point2 a,
                                 geometry::Point2 b);
/// Between [p, q] and a ring's edges.
SegmentDistance ring_distance(geometry::Point2 p, geometry::Point2 q, const geometry::Ring& ring);
/// Between [p, q] and the area a ring encloses (0 when it enters it).
SegmentDistance zone_distance(geometry::Point2 p, geometry::Point2 q, const geometry::Ring& ring);

/// A zone or fence in local metres: a ring, or a circle (its centre alone in `ring`).
struct LocalZone {
  std::string name;
  geometry::Ring ring;
  double radius_m = 0.0;   ///< > 0: a circle
  bool own_fence = false;  ///< the file's own exclusion fence: not entered (no clearance)
  /// How far the ring may stray from the shape it stands for: its edges, straight in longitude
  /// and latitude, bow from their chords in a frame, and swath plan reads a zone's within 5 cm
  /// of the edge as drawn (geometry::kZoneEdgeDepartureTolerance_m): the most they bow, up to that.
  double slack_m = 0.0;
};

/// A straight piece of the flight to check: a leg or a stopping overrun.
struct PathPiece {
  Point3 from, to;
  std::string place;
  bool overrun = false;
};
std::vector<PathPiece> pieces(const FlownPath& path);
std::string piece_name(const PathPiece& piece);
/// What a violation's sentence adds when it was found on ArduPilot's track (autopilot_track.hpp),
/// which strays up to `bow_m` from the straight leg ("" for 0: on the straight leg).
std::string on_track(double bow_m);

/// One drone file being checked.
struct FileContext {
  std::string source;
  const FlownPath* path = nullptr;
  const geometry::LocalFrame* frame = nullptr;
  std::vector<geometry::Point2> rally_points;
  double home_ground_amsl_m = 0.0;  ///< the DEM's height at home
};

/// What the checks found, accumulated over files.
struct Checked {
  std::vector<Violation> violations;
  double least_clearance_m = std::numeric_limits<double>::infinity();
  std::string least_clearance_where;
  bool fence_checked = false;
  bool fence_across_antimeridian = false;  ///< an inclusion fence left out: it crosses ±180°
  double least_fence_margin_m = std::numeric_limits<double>::infinity();
  std::size_t most_inclusion_fences = 0;  ///< in one file
  double max_height_m = -std::numeric_limits<double>::infinity();
  double min_height_m = std::numeric_limits<double>::infinity();
  double photos = 0, transit_photos = 0;
  int photo_legs = 0;
};

void check_zones(const FileContext& f, const std::vector<LocalZone>& zones, double clearance_m,
                 Checked& out);
/// Every piece, the home and the rally points inside every one of `fences` (ArduPilot's default,
/// PX4's rule), or with `any_one` inside at least one (ArduPilot's FENCE_OPTIONS bit 2).
void check_fences(const FileContext& f, const std::vector<LocalZone>& fences, bool any_one,
                  Checked& out);
void check_heights(const FileContext& f, const CheckOptions& options, Checked& out);
void check_photos(const FileContext& f, const std::vector<geometry::Ring>& area, Checked& out);

}  // namespace swath::preflight
