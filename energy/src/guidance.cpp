#include "swath/energy/guidance.hpp"

#include <algorithm>
#include <cmath>

#include "swath/base/input_error.hpp"

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
    const std::vector<double> values(names.size(), 0.0);
    out.push_back(StageField{static_cast<int>(k),
                             where,
                             Expression(s.phi, names, where),
                             values,
                             s.gain,
                             s.direction,
                             {},
                             Expression(s.trigger_x, names, where),
                             Expression(s.trigger_y, names, where),
                             s.trajectory});
    set_trajectory_parameters(out.back(), c);
  }
  return out;
}

void set_trajectory_parameters(StageField& stage, const std::vector<double>& c) {
  const std::vector<double> params = stage_parameters(stage.bounds, c);
  std::copy(params.begin(), params.end(), stage.values.begin() + 2);
  stage.values[0] = stage.values[1] = 0.0;  // a triggering point depends on c1.. only
  const geometry::Point2 trigger{stage.trigger_x(stage.values), stage.trigger_y(stage.values)};
  if (!std::isfinite(trigger.x) || !std::isfinite(trigger.y)) {
    std::string msg = stage.where;
    msg += ": the triggering point is not a finite number for these parameters";
    throw base::InputError(msg);
  }
  stage.trigger = trigger;
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
  const double g = std::sqrt(f.gradient.x * f.gradient.x + f.gradient.y * f.gradient.y);
  const double v = std::sqrt(f.velocity.x * f.velocity.x + f.velocity.y * f.velocity.y);
  if (!std::isfinite(v) || g < 1e-9 || v < 1e-12 * (1.0 + g)) return std::nullopt;
  return Point2{f.velocity.x / v, f.velocity.y / v};
}

}  // namespace swath::energy
