#pragma once
// Scaling a survey's line spacing about the middle of its lanes, and how far it can go before the
// camera coverage drops below a minimum (the trajectory parameter c1 of a survey's energy plan).

#include <vector>

#include "swath/planning/survey.hpp"

namespace swath::planning {

/// A line's place across the sweep: its offset along the lanes' normal n = (-sin a, cos a), a the
/// lines' angle (degrees counter-clockwise from the local x axis), in metres from the origin.
double lane_offset_m(const SweepLine& line, double angle_deg);

/// The middle of the lanes' offsets (halfway between the lowest and the highest), metres.
double lane_middle_m(const std::vector<SweepLine>& lines, double angle_deg);

/// The lines moved across the sweep so that each offset d becomes middle + (d - middle) * scale:
/// the spacing times `scale` (> 0), along-track extents and directions unchanged.
std::vector<SweepLine> scale_line_spacing(const std::vector<SweepLine>& lines, double angle_deg,
                                          double middle_m, double scale);

struct SpacingScaleBounds {
  double lo = 1.0, hi = 1.0;            ///< scales of the line spacing, lo <= 1 <= hi
  double nominal_covered_fraction = 0;  ///< coverage at scale 1 (the plan as written)
  double lo_covered_fraction = 0;       ///< coverage at lo
  double hi_covered_fraction = 0;       ///< coverage at hi
  double middle_m = 0.0;                ///< the lanes' middle the scale is taken about
};

/// The interval of spacing scales around 1, within [min_scale, max_scale], over which every
/// drone's lines together still cover at least `min_covered_fraction` (in (0, 1]) of the area
/// (measure_coverage). Found by a scan in steps of 0.01 outwards from 1 and bisection of the first
/// failing step to 1e-5, so the bounds are exact to 1e-5 where coverage is monotone on each side of
/// 1, and the interval never holds a failing scan point. {1, 1} when the plan itself falls short.
SpacingScaleBounds spacing_scale_bounds(const SurveyPlan& plan, double min_covered_fraction,
                                        double min_scale = 0.5, double max_scale = 1.0);

}  // namespace swath::planning
