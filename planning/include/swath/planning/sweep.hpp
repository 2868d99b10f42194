#pragma once
// Zigzag sweep of an area (docs/swath-plan.md, paper 001 Algorithm 2).

#include <optional>
#include <vector>

#include "swath/geometry/min_height.hpp"
#include "swath/geometry/polygon.hpp"

namespace swath::planning {

/// How flight lines are spread over the area's height (perpendicular to the lines).
enum class LinePlacement {
  /// The fewest lines whose footprints cover the height, at the given spacing, centred.
  centered,
  /// Paper 001 Algorithm 2: first line half a spacing above the bottom, then one spacing apart;
  /// the last one half a spacing after the one before it (or at the top).
  paper,
};

/// How far a line reaches along its ordinate.
enum class SegmentRule {
  /// docs/swath-plan.md: the area's extent within the line's whole strip, so slanted edges leave no
  /// unseen triangles (the line may pass the boundary there).
  strip,
  /// The area's own extent at the line's ordinate: never leaves a cell that every line meets in one
  /// interval (boustrophedon cells); slivers at slanted sides rely on the footprint's width.
  inside,
};

struct SweepSettings {
  /// Direction of the lines, degrees counter-clockwise from the local x axis (east), any value.
  double angle_deg = 0.0;
  double line_spacing_m = 0.0;     ///< > 0
  double footprint_width_m = 0.0;  ///< camera footprint across the line, >= line_spacing_m
  LinePlacement placement = LinePlacement::centered;
  double turnaround_m = 0.0;  ///< extension beyond both ends of every line, >= 0
  SegmentRule segments = SegmentRule::strip;
  /// When not empty: fly exactly these ordinates (perpendicular offsets in the frame rotated by
  /// -angle_deg, increasing) that fall within the area, instead of placing lines; one line at
  /// mid-height if none does. Lets cells of one area share a lane grid.
  std::vector<double> ordinates;
  /// Inside rule: where the area juts out along the lines between two lanes (farther than its
  /// extent at either lane's ordinate, by over 2 % of the spacing), add a lane through the
  /// outermost point of the protrusion, so that its footprint covers it without leaving the area.
  bool fill_protrusions = false;
};

/// One flight line in the local frame, in the direction it is flown.
struct SweepLine {
  geometry::Point2 start;
  geometry::Point2 end;
};

struct Sweep {
  double angle_deg = 0.0;  ///< as in SweepSettings, normalised to [0, 180)
  double height_m = 0.0;   ///< extent of the area perpendicular to the lines
  /// Bottom to top in the rotated frame (lines' left side), all flown towards +x of the rotated
  /// frame. order_lines() turns this into a zigzag.
  std::vector<SweepLine> lines;
};

/// Places lines over `area` (all rings; holes ignored for the extent, so pass the area to fly).
/// With SegmentRule::strip each line's segment spans the area's extent within its strip: the
/// band between the midpoints to its neighbours (the first from the bottom, the last to the top).
/// Every point of the area then lies in some strip, within the line's segment span and within
/// half a footprint of the line, so it is seen (docs/swath-plan.md guarantee). With
/// SegmentRule::inside the segment is the area's extent at the line's own ordinate. Lines that
/// would hold no area are dropped. Throws std::invalid_argument on settings out of range.
Sweep plan_sweep(const geometry::Polygon& area, const SweepSettings& settings);

/// Each line's turnarounds (its first and last `turnaround_m`, the extension plan_sweep() and the
/// split add beyond both ends) cut where they first meet `keep_out` (the no-fly zones grown by the
/// clearance, each part's outer ring then its holes: the even-odd rule), dropped where the line's
/// own end lies in or on it: a turnaround flown into a zone's clearance band broke the clearance
/// the lines themselves keep. Lines whose turnarounds meet nothing are left as they are.
void keep_turnarounds_out(std::vector<SweepLine>& lines, double turnaround_m,
                          const std::vector<geometry::Ring>& keep_out);

/// Line offsets (rotated-frame y) for an area spanning [y_min, y_max].
std::vector<double> line_offsets(double y_min, double y_max, double spacing_m,
                                 double footprint_width_m, LinePlacement placement);

/// The lines of `sweep` as a zigzag: from the top or bottom line, the first flown towards -x of
/// the rotated frame or +x, directions alternating.
std::vector<SweepLine> zigzag(const Sweep& sweep, bool top_first, bool reverse_first);

/// Where the survey starts.
enum class StartCorner { nearest_home, sw, se, nw, ne };

/// Orders and directs the lines of `sweep` into a zigzag (alternating directions) starting at the
/// end chosen by `start`: the corner most to the south-west (etc.) of the four possible entry
/// points, or for nearest_home the variant whose home -> first and last -> home legs are shortest
/// (`home` required then).
std::vector<SweepLine> order_lines(const Sweep& sweep, StartCorner start,
                                   std::optional<geometry::Point2> home = std::nullopt);

/// Points along a line every `spacing_m` at most (evenly), ends included.
std::vector<geometry::Point2> line_waypoints(const SweepLine& line,
                                             std::optional<double> spacing_m);

/// Rotates p by angle_deg counter-clockwise about the origin.
geometry::Point2 rotate(geometry::Point2 p, double angle_deg);

}  // namespace swath::planning
