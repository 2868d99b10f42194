#pragma once
// The guidance vector field of paper 004 eq. 3 for the stages of a plan.

#include <optional>
#include <string>
#include <vector>

#include "swath/energy/expression.hpp"
#include "swath/energy/plan.hpp"
#include "swath/geometry/point.hpp"

namespace swath::energy {

/// One stage with its parameters fixed: phi compiled, triggering point evaluated.
struct StageField {
  int stage = 0;                    ///< 0-based index in the plan
  std::string where;                ///< "survey.stages: line 13" for messages
  Expression phi;                   ///< over x, y, c1..
  std::vector<double> values;       ///< x, y, c1.. (x, y rewritten at each evaluation)
  double gain = 0.0;                ///< k_e
  int direction = 1;                ///< +1 counter-clockwise, -1 clockwise
  geometry::Point2 trigger;         ///< local metres
  Expression trigger_x, trigger_y;  ///< over the same variables (x, y read as 0)
  std::vector<Interval> bounds;     ///< of the trajectory parameters
};

/// The stages of `plan` with trajectory parameters `c` (one per parameter of the plan), each
/// clamped into the stage's bounds. Throws base::InputError when a triggering point is not
/// finite for these parameters (e.g. sqrt of a negative number).
std::vector<StageField> stage_fields(const Plan& plan, const std::vector<double>& c);

/// Changes the stage's trajectory parameters (clamped into its bounds): phi's values and the
/// triggering point. Throws base::InputError when the triggering point is not finite.
void set_trajectory_parameters(StageField& stage, const std::vector<double>& c);

/// `values` clamped into `bounds`, one per bound (missing values: the bound's upper end).
std::vector<double> stage_parameters(const std::vector<Interval>& bounds,
                                     const std::vector<double>& values);

/// The field at a point: phi, its gradient (central differences, step 1 mm) and the desired
/// velocity p_d' = D grad(phi) - k_e phi grad(phi), where D rotates by +90 degrees for a
/// counter-clockwise stage and by -90 for a clockwise one. (For phi growing outwards from a closed
/// curve, +90 circulates counter-clockwise; the paper's matrix E = [[0, 1], [-1, 0]] is the -90
/// rotation, and its survey example only flies as drawn with +90 for rotation 90.)
struct FieldSample {
  double phi = 0.0;
  geometry::Point2 gradient;
  geometry::Point2 velocity;  ///< not normalised
};

FieldSample guidance_field(StageField& stage, geometry::Point2 p);

/// The unit direction of the field at p, or empty where the field vanishes (gradient zero, or
/// the two terms cancel).
std::optional<geometry::Point2> guidance_direction(StageField& stage, geometry::Point2 p);

}  // namespace swath::energy
