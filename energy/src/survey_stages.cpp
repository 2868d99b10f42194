#include "swath/energy/survey_stages.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "swath/base/number_text.hpp"

namespace swath::energy {
namespace {

using base::round_to;
using base::shortest_text;
using geometry::Point2;

// `constant + c1_coefficient * c1 (+ x_coefficient * x + y_coefficient * y)` as plan text.
struct Linear {
  double constant = 0, c1 = 0, x = 0, y = 0;
};

std::string text(const Linear& e) {
  std::string out;
  auto term = [&out](double coefficient, const char* name, int decimals) {
    const double v = round_to(coefficient, decimals);
    if (v == 0.0 && name[0] != '\0') return;
    if (!out.empty() && v >= 0) out += '+';
    out += shortest_text(v);
    if (name[0] != '\0') (out += '*') += name;
  };
  term(e.x, "x", 9);
  term(e.y, "y", 9);
  term(e.c1, "c1", 6);
  if (out.empty() || round_to(e.constant, 6) != 0.0) term(e.constant, "", 6);
  return out;
}

// A point on the lanes' grid: t along the lines, offset middle + k c1 across them.
struct GridPoint {
  double t = 0, k = 0;
};

class Frame {
 public:
  Frame(double angle_deg, double middle_m) : middle_(middle_m) {
    const double a = angle_deg * std::numbers::pi / 180;
    u_ = {std::cos(a), std::sin(a)};
    n_ = {-u_.y, u_.x};
  }
  Point2 u() const { return u_; }
  GridPoint grid(Point2 p) const { return {geometry::dot(p, u_), geometry::dot(p, n_) - middle_}; }
  Point2 local(GridPoint g, double c1) const { return u_ * g.t + n_ * (middle_ + g.k * c1); }
  Linear x(GridPoint g) const { return {g.t * u_.x + middle_ * n_.x, g.k * n_.x}; }
  Linear y(GridPoint g) const { return {g.t * u_.y + middle_ * n_.y, g.k * n_.y}; }

 private:
  double middle_;
  Point2 u_, n_;
};

struct StageBuilder {
  const Frame& frame;
  const SurveyStageSettings& settings;
  Plan plan;

  void add(double gain, int direction, const std::string& phi, const Linear& trigger_x,
           const Linear& trigger_y, bool computing) {
    Stage s;
    s.gain = round_to(gain, 9);
    s.direction = direction;
    s.phi = phi;
    s.trigger_x = text(trigger_x);
    s.trigger_y = text(trigger_y);
    s.trajectory = {settings.spacing_scale};
    s.computations = settings.computations;
    if (!computing)
      for (Interval& c : s.computations) c = {0, 0};
    plan.stages.push_back(std::move(s));
  }

  // Along the direction `w` (unit, fixed) to the point `to` (grid point, or fixed local point).
  // phi = v . p - v . to with v = w turned +90 degrees; clockwise rotation of grad phi = v is +w.
  void straight(Point2 w, const Linear& to_x, const Linear& to_y, bool computing) {
    const Point2 v{-w.y, w.x};
    Linear phi{-(v.x * to_x.constant + v.y * to_y.constant), -(v.x * to_x.c1 + v.y * to_y.c1), v.x,
               v.y};
    add(4 / settings.line_spacing_m, -1, text(phi), to_x, to_y, computing);
  }
  void straight_to_grid(Point2 w, GridPoint to) { straight(w, frame.x(to), frame.y(to), true); }

  // Half circle about `centre` of radius |radius_k| c1 from the current lane to the lane of
  // `to`; counter-clockwise when `ccw`.
  void turn(GridPoint centre, double radius_k, bool ccw, GridPoint to) {
    const Linear cx = frame.x(centre), cy = frame.y(centre);
    const std::string phi = "(x-(" + text(cx) + "))^2+(y-(" + text(cy) + "))^2-(" +
                            text(Linear{0, std::abs(radius_k)}) + ")^2";
    add(1 / (radius_k * radius_k), ccw ? 1 : -1, phi, frame.x(to), frame.y(to), true);
  }
};

}  // namespace

Plan survey_stage_plan(const SurveyLines& mission, const SurveyStageSettings& settings) {
  if (mission.lines.empty())
    throw std::invalid_argument("survey_stage_plan: drone " + std::to_string(mission.drone) +
                                " has no lines");
  if (!(settings.line_spacing_m > 0))
    throw std::invalid_argument("survey_stage_plan: line spacing must be > 0");
  if (!(settings.spacing_scale.lo > 0 && settings.spacing_scale.lo <= 1 &&
        settings.spacing_scale.hi >= 1))
    throw std::invalid_argument("survey_stage_plan: c1 bounds must hold 1 and stay > 0");

  const Frame frame(settings.angle_deg, settings.middle_m);
  StageBuilder b{frame, settings, {}};
  const auto& lines = mission.lines;
  const std::size_t count = lines.size();
  std::vector<GridPoint> start(count), end(count);
  std::vector<int> along(count);  // +1 flown towards +u, -1 towards -u
  for (std::size_t i = 0; i < count; ++i) {
    start[i] = frame.grid(lines[i].start);
    end[i] = frame.grid(lines[i].end);
    along[i] = end[i].t >= start[i].t ? 1 : -1;
    end[i].k = start[i].k = (start[i].k + end[i].k) / 2;
  }
  auto unit = [](Point2 d) { return d * (1 / std::sqrt(geometry::dot(d, d))); };
  auto lane = [&](std::size_t i) { return frame.u() * along[i]; };

  if (geometry::distance(mission.home, frame.local(start[0], 1)) >= 1)
    b.straight(unit(frame.local(start[0], 1) - mission.home), frame.x(start[0]), frame.y(start[0]),
               false);
  for (std::size_t i = 0; i < count; ++i) {
    const bool last = i + 1 == count;
    const double gap_k = last ? 0 : start[i + 1].k - end[i].k;
    const bool u_turn = !last && along[i + 1] == -along[i] && std::abs(gap_k) > 1e-6 &&
                        std::abs(gap_k) <= 1.5 * settings.line_spacing_m;
    if (u_turn) {
      const double t =
          along[i] > 0 ? std::max(end[i].t, start[i + 1].t) : std::min(end[i].t, start[i + 1].t);
      b.straight_to_grid(lane(i), {t, end[i].k});
      start[i + 1].t = t;
      b.turn({t, end[i].k + gap_k / 2}, gap_k / 2, along[i] * gap_k > 0, start[i + 1]);
      continue;
    }
    b.straight_to_grid(lane(i), end[i]);
    if (!last && geometry::distance(frame.local(start[i + 1], 1), frame.local(end[i], 1)) > 1e-6)
      b.straight_to_grid(unit(frame.local(start[i + 1], 1) - frame.local(end[i], 1)), start[i + 1]);
  }
  if (geometry::distance(mission.home, frame.local(end[count - 1], 1)) >= 1)
    b.straight(unit(mission.home - frame.local(end[count - 1], 1)), {mission.home.x},
               {mission.home.y}, false);
  return b.plan;
}

}  // namespace swath::energy
