#include "swath/planning/spacing_scale.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace swath::planning {
namespace {

geometry::Point2 lane_normal(double angle_deg) {
  const double a = angle_deg * std::numbers::pi / 180;
  return {-std::sin(a), std::cos(a)};
}

}  // namespace

double lane_offset_m(const SweepLine& line, double angle_deg) {
  // Both ends lie on the lane; their mean is the steadier figure after rotation round trips.
  return geometry::dot(line.start + line.end, lane_normal(angle_deg)) / 2;
}

double lane_middle_m(const std::vector<SweepLine>& lines, double angle_deg) {
  if (lines.empty()) return 0.0;
  double lo = INFINITY, hi = -INFINITY;
  for (const SweepLine& l : lines) {
    const double d = lane_offset_m(l, angle_deg);
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  return (lo + hi) / 2;
}

std::vector<SweepLine> scale_line_spacing(const std::vector<SweepLine>& lines, double angle_deg,
                                          double middle_m, double scale) {
  if (!(scale > 0)) throw std::invalid_argument("scale_line_spacing: scale must be > 0");
  const geometry::Point2 n = lane_normal(angle_deg);
  std::vector<SweepLine> out;
  out.reserve(lines.size());
  for (const SweepLine& l : lines) {
    const double d = lane_offset_m(l, angle_deg);
    const geometry::Point2 shift = n * ((middle_m + (d - middle_m) * scale) - d);
    out.push_back({l.start + shift, l.end + shift});
  }
  return out;
}

SpacingScaleBounds spacing_scale_bounds(const SurveyPlan& plan, double min_covered_fraction,
                                        double min_scale, double max_scale) {
  if (!(min_covered_fraction > 0 && min_covered_fraction <= 1))
    throw std::invalid_argument("spacing_scale_bounds: minimum coverage must be in (0, 1]");
  if (!(min_scale > 0 && min_scale <= 1 && max_scale >= 1))
    throw std::invalid_argument("spacing_scale_bounds: need 0 < min_scale <= 1 <= max_scale");
  std::vector<SweepLine> lines;
  for (const DronePlan& d : plan.drones)
    lines.insert(lines.end(), d.mission.lines.begin(), d.mission.lines.end());
  const geometry::Polygon area = measured_area(plan);
  const double angle = plan.sweep.angle_deg;
  const double width = plan.imaging.footprint_across_m;

  SpacingScaleBounds bounds;
  bounds.middle_m = lane_middle_m(lines, angle);
  auto covered = [&](double scale) {
    return measure_coverage(area, scale_line_spacing(lines, angle, bounds.middle_m, scale), angle,
                            width)
        .covered_fraction;
  };
  bounds.nominal_covered_fraction = covered(1.0);
  bounds.lo_covered_fraction = bounds.hi_covered_fraction = bounds.nominal_covered_fraction;
  if (lines.empty() || bounds.nominal_covered_fraction < min_covered_fraction) return bounds;

  // Outwards from 1 in `step`s to the first failing scale, then bisect between the last good one
  // and it. Returns the good end and its coverage.
  auto edge = [&](double step, double limit) {
    double good = 1.0, good_fraction = bounds.nominal_covered_fraction;
    for (int i = 1;; ++i) {
      double s = 1.0 + step * i;
      if ((step > 0 && s > limit) || (step < 0 && s < limit)) s = limit;
      const double f = covered(s);
      if (f < min_covered_fraction) {
        double bad = s;
        while (std::abs(bad - good) > 1e-5) {
          const double mid = (good + bad) / 2;
          const double fm = covered(mid);
          if (fm >= min_covered_fraction) {
            good = mid;
            good_fraction = fm;
          } else {
            bad = mid;
          }
        }
        return std::pair{good, good_fraction};
      }
      good = s;
      good_fraction = f;
      if (s == limit) return std::pair{good, good_fraction};
    }
  };
  std::tie(bounds.lo, bounds.lo_covered_fraction) = edge(-0.01, min_scale);
  std::tie(bounds.hi, bounds.hi_covered_fraction) = edge(0.01, max_scale);
  return bounds;
}

}  // namespace swath::planning
