#pragma once
// A survey's zigzag as a plan of flight stages (docs/swath-energy.md), so that swath-energy can
// fly, evaluate and replan a real survey: lines as line stages, turns as half-circle stages, and
// the trajectory parameter c1 scaling the line spacing.

#include <vector>

#include "swath/energy/plan.hpp"
#include "swath/geometry/point.hpp"

namespace swath::energy {

/// One drone's survey as a plan flies it (swath plan's planning::DroneMission gives it): its home
/// and its lines in flight order, each flown from start to end; local metres (x east, y north).
struct SurveyLines {
  struct Line {
    geometry::Point2 start, end;
  };
  int drone = 1;  ///< 1-based, for messages
  geometry::Point2 home;
  std::vector<Line> lines;
};

struct SurveyStageSettings {
  double angle_deg = 0.0;       ///< the lines' angle, degrees counter-clockwise from local x (east)
  double line_spacing_m = 0.0;  ///< the planned spacing (> 0): sets the gains, finds the turns
  /// c1 scales every lane's offset d about this middle: d(c1) = middle + (d - middle) c1, metres
  /// along the lanes' normal (-sin a, cos a) (planning::lane_offset_m).
  double middle_m = 0.0;
  Interval spacing_scale{1.0, 1.0};  ///< bounds of c1; 1 is the plan as written
  /// Bounds of each computation parameter on the survey's lines and turns; the legs from and to
  /// home switch them off ([0, 0]).
  std::vector<Interval> computations;
};

/// One drone's survey as stages in its local frame (x east, y north, metres): the leg from home
/// to the first line (left out when shorter than 1 m), each line, between two lines that are
/// flown in opposite directions at most 1.5 spacings apart a half circle whose diameter joins
/// them (the shorter line extended to the longer one's end, so that the circle closes), otherwise
/// a straight transit, and the leg back home, which ends the mission. Straight stages have gain
/// 4 / spacing (the correction matches the pull along the line at a quarter spacing off it),
/// circles 1 / r^2 (likewise at half a radius). Every point, circle centre and radius is linear in
/// c1; the along-track extents do not change with it. The lanes' directions are fixed, so a
/// transit whose ends move with c1 is aimed at its end along the direction planned for c1 = 1.
/// Throws std::invalid_argument for a mission without lines or settings out of range.
Plan survey_stage_plan(const SurveyLines& mission, const SurveyStageSettings& settings);

}  // namespace swath::energy
