#include "swath/energy/guidance.hpp"

#include <algorithm>
#include <cmath>

#include "swath/geometry/input_error.hpp"

namespace swath::energy {

using geometry::Point2;

std::vector<double> stage_parameters(const std::vector<Interval>& bounds,
                                     const std::vector<double>& values) {
  std::vector<double> out;
  for (std::size_t i = 0; i < bounds.size(); ++i)
    out.push_back(i < values.size() ? std::clamp(values[i], bounds[i].lo, bounds[i].hi)
                                    : bounds[i].hi);
  return out;
}

std::vector<StageField> stage_fields(const Plan& plan, const std::vector<double>& c) {
  std::vector<std::string> names{"x", "y"};
  for (std::size_t i = 1; i <= plan.trajectory_parameters(); ++i) {
    std::string name = "c";
    name += std::to_string(i);
    names.push_back(name);
  }
  std::vector<StageField> out;
  for (std::size_t k = 0; k < plan.stages.size(); ++k) {
    const Stage& s = plan.stages[k];
    std::string where = plan.source;
    where += s.line > 0 ? ": line " + std::to_string(s.line) : ": stage " + std::to_string(k + 1);
    std::vector<double> values{0.0, 0.0};
    const std::vector<double> params = stage_parameters(s.trajectory, c);
    values.insert(values.end(), params.begin(), params.end());
    const Expression tx(s.trigger_x, names, where), ty(s.trigger_y, names, where);
    const Point2 trigger{tx(values), ty(values)};
    if (!std::isfinite(trigger.x) || !std::isfinite(trigger.y)) {
      std::string msg = where;
      msg += ": the triggering point is not a finite number for these parameters";
      throw geometry::InputError(msg);
    }
    out.push_back(StageField{static_cast<int>(k), where, Expression(s.phi, names, where), values,
                             s.gain, s.direction, trigger});
  }
  return out;
}

FieldSample guidance_field(StageField& stage, Point2 p) {
  constexpr double h = 1e-3;  // central differences: error ~ h^2 phi''' + eps |phi| / h
  auto phi_at = [&](double x, double y) {
    stage.values[0] = x;
    stage.values[1] = y;
    return stage.phi(stage.values);
  };
  FieldSample f;
  f.phi = phi_at(p.x, p.y);
  f.gradient = {(phi_at(p.x + h, p.y) - phi_at(p.x - h, p.y)) / (2 * h),
                (phi_at(p.x, p.y + h) - phi_at(p.x, p.y - h)) / (2 * h)};
  const double d = stage.direction;
  const Point2 tangent{-d * f.gradient.y, d * f.gradient.x};
  f.velocity = {tangent.x - stage.gain * f.phi * f.gradient.x,
                tangent.y - stage.gain * f.phi * f.gradient.y};
  return f;
}

std::optional<Point2> guidance_direction(StageField& stage, Point2 p) {
  const FieldSample f = guidance_field(stage, p);
  const double g = std::hypot(f.gradient.x, f.gradient.y);
  const double v = std::hypot(f.velocity.x, f.velocity.y);
  if (!std::isfinite(v) || g < 1e-9 || v < 1e-12 * (1.0 + g)) return std::nullopt;
  return Point2{f.velocity.x / v, f.velocity.y / v};
}

}  // namespace swath::energy
