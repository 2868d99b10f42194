#include "swath/energy/survey_stages.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "swath/energy/guidance.hpp"
#include "swath/energy/simulation.hpp"

namespace swath::energy {
namespace {

using geometry::Point2;

// Four lanes 20 m apart at `angle_deg`, flown as a zigzag whose ends differ (a slanted field
// side), from a home 30 m before the first line.
struct Zigzag {
  double angle_deg = 0, spacing_m = 20;
  Point2 u, n;
  SurveyLines mission;
  Point2 at(double t, double d) const { return u * t + n * d; }
};

Zigzag zigzag(double angle_deg) {
  Zigzag z;
  z.angle_deg = angle_deg;
  const double a = angle_deg * std::numbers::pi / 180;
  z.u = {std::cos(a), std::sin(a)};
  z.n = {-z.u.y, z.u.x};
  const double lo[] = {0, 5, 10, 15}, hi[] = {200, 190, 205, 180};
  for (int i = 0; i < 4; ++i) {
    const double d = 50 + i * z.spacing_m;
    const Point2 a_end = z.at(lo[i], d), b_end = z.at(hi[i], d);
    z.mission.lines.push_back(i % 2 == 0 ? SurveyLines::Line{a_end, b_end}
                                         : SurveyLines::Line{b_end, a_end});
  }
  z.mission.home = z.at(-30, 50);
  return z;
}

SurveyStageSettings settings_for(const Zigzag& z) {
  SurveyStageSettings s;
  s.angle_deg = z.angle_deg;
  s.line_spacing_m = z.spacing_m;
  s.middle_m = 80;  // lanes at offsets 50..110
  s.spacing_scale = {0.8, 1.0};
  s.computations = {{2, 10}};
  return s;
}

TEST(SurveyStagePlan, StagesFollowTheLanesAndTurnOnHalfCirclesForEveryC1) {
  for (double angle : {0.0, 37.0, 90.0, 151.0}) {
    const Zigzag z = zigzag(angle);
    const Plan plan = survey_stage_plan(z.mission, settings_for(z));
    // home leg, 4 lines, 3 turns, return leg
    ASSERT_EQ(plan.stages.size(), 9u) << angle;
    EXPECT_EQ(format_plan(parse_plan(format_plan(plan), "round trip")), format_plan(plan));
    EXPECT_EQ(plan.stages.front().computations[0], (Interval{0, 0}));
    EXPECT_EQ(plan.stages[1].computations[0], (Interval{2, 10}));
    for (double c1 : {0.8, 0.9, 1.0}) {
      auto fields = stage_fields(plan, {c1});
      auto offset = [&](int lane) { return 80 + (lane * z.spacing_m - 30) * c1; };
      // Lines end where the next turn begins: at the farther of the two lanes' ends.
      const double turn_t[] = {200, 5, 205};
      for (int lane = 0; lane < 4; ++lane) {
        StageField& line = fields[1 + 2 * lane];
        const double end_t = lane < 3 ? turn_t[lane] : 15;
        const Point2 end = z.at(end_t, offset(lane));
        EXPECT_NEAR(geometry::distance(line.trigger, end), 0, 1e-5) << angle << " " << c1;
        EXPECT_NEAR(guidance_field(line, z.at(100, offset(lane))).phi, 0, 1e-5);
        // Along the lane in its flight direction.
        const auto dir = guidance_direction(line, z.at(100, offset(lane)));
        ASSERT_TRUE(dir);
        EXPECT_NEAR(geometry::dot(*dir, z.u * (lane % 2 == 0 ? 1 : -1)), 1, 1e-9);
        if (lane == 3) break;
        StageField& turn = fields[2 + 2 * lane];
        // The circle passes through both lanes' ends (phi ~ 2 r e: 1e-4 is 5 um off it), and
        // leaves the line tangentially.
        EXPECT_NEAR(guidance_field(turn, end).phi, 0, 1e-4);
        EXPECT_NEAR(guidance_field(turn, turn.trigger).phi, 0, 1e-4);
        EXPECT_NEAR(geometry::distance(turn.trigger, z.at(end_t, offset(lane + 1))), 0, 1e-5);
        const auto tangent = guidance_direction(turn, end);
        ASSERT_TRUE(tangent);
        EXPECT_NEAR(geometry::dot(*tangent, *dir), 1, 1e-6) << angle << " lane " << lane;
      }
      EXPECT_NEAR(geometry::distance(fields.back().trigger, z.mission.home), 0, 1e-6);
    }
  }
}

TEST(SurveyStagePlan, TheSimulatedDroneFliesTheLanesAndLowerC1ShortensOnlyTheTurns) {
  const Zigzag z = zigzag(37);
  const Plan plan = survey_stage_plan(z.mission, settings_for(z));
  SimConfig config;
  config.source = "test.yaml";
  config.speed_m_s = 5;
  config.trigger_radius_m = 2;
  config.start = z.mission.home;
  config.power.noise_w = 0;
  config.replan = false;
  config.output_interval_s = 0.1;
  config.power.computations = {{"detection", {{2, 4.75}, {10, 9.75}}}};
  double time_at_1 = 0;
  for (double c1 : {1.0, 0.8}) {
    config.trajectory_parameters = {c1};
    const SimulationResult r = simulate(plan, config);
    ASSERT_EQ(r.status, SimulationEnd::completed) << c1;
    // Once on a lane (past its first 20 m), the drone stays within 0.3 m of it.
    double worst = 0;
    for (const FlightSample& s : r.samples) {
      if (s.stage < 1 || s.stage > 7 || s.stage % 2 == 0) continue;
      const int lane = (s.stage - 1) / 2;
      const double t = geometry::dot(s.position, z.u);
      const double start_t[] = {0, 200, 5, 205};
      if (std::abs(t - start_t[lane]) < 20) continue;
      const double d = geometry::dot(s.position, z.n);
      worst = std::max(worst, std::abs(d - (80 + (lane * z.spacing_m - 30) * c1)));
    }
    EXPECT_LT(worst, 0.3) << c1;
    if (c1 == 1.0) {
      time_at_1 = r.flight_time_s;
    } else {
      // Three half circles of radius 10 c1: pi * 10 * 0.2 m shorter each, at 5 m/s; the legs
      // from and to home change a little with the first and last lanes' places.
      const double turns_s = 3 * std::numbers::pi * 10 * 0.2 / 5;
      EXPECT_LT(r.flight_time_s, time_at_1);
      EXPECT_NEAR(time_at_1 - r.flight_time_s, turns_s, 0.35 * turns_s);
    }
  }
}

TEST(SurveyStagePlan, FarApartOrSameDirectionLinesAreJoinedByTransits) {
  Zigzag z = zigzag(0);
  // The third line flown the same way as the second: no U-turn between them.
  std::swap(z.mission.lines[2].start, z.mission.lines[2].end);
  std::swap(z.mission.lines[3].start, z.mission.lines[3].end);
  const Plan plan = survey_stage_plan(z.mission, settings_for(z));
  auto fields = stage_fields(plan, {1.0});
  // home, line, turn, line, transit, line, turn, line, home
  ASSERT_EQ(fields.size(), 9u);
  EXPECT_EQ(fields[4].phi.text().find('^'), std::string::npos);  // straight
  EXPECT_NEAR(geometry::distance(fields[4].trigger, z.mission.lines[2].start), 0, 1e-6);
  EXPECT_THROW(survey_stage_plan(SurveyLines{}, settings_for(z)), std::invalid_argument);
}

}  // namespace
}  // namespace swath::energy
