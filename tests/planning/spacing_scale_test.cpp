#include "swath/planning/spacing_scale.hpp"
#include "meadow_survey.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "coverage_oracle.hpp"
#include "swath/geometry/field.hpp"
#include "swath/planning/camera.hpp"

namespace swath::planning {
namespace {

using geometry::Point2;

SurveyPlan rectangle_plan(double width_m, double height_m) {
  SurveyRequest r;
  r.field.source = "rectangle";
  r.field.polygon.outer = {{0, 0}, {width_m, 0}, {width_m, height_m}, {0, height_m}};
  r.field.source_index = {{0, 1, 2, 3}};
  geometry::place_local_field(r.field, {47.0, 8.0, 0.0});
  r.camera = {"test", 23.2, 15.4, 16, 5456, 3632, std::nullopt};
  PhotogrammetryMode m;
  m.altitude_m = 40;  // footprint 58 m, spacing 17.4 m
  r.mode = m;
  return plan_survey(r);
}

TEST(ScaleLineSpacing, ScalesOffsetsAboutTheMiddleAndKeepsTheLinesAlongTrack) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(-500, 500), angle(0, 180), scale(0.3, 2.5);
  for (int round = 0; round < 50; ++round) {
    const double a = angle(rng), c = scale(rng), middle = coord(rng);
    const Point2 u{std::cos(a * std::numbers::pi / 180), std::sin(a * std::numbers::pi / 180)};
    std::vector<SweepLine> lines;
    for (int i = 0; i < 6; ++i) {
      const Point2 p{coord(rng), coord(rng)};
      lines.push_back({p, p + u * coord(rng)});
    }
    const auto scaled = scale_line_spacing(lines, a, middle, c);
    ASSERT_EQ(scaled.size(), lines.size());
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const double d = lane_offset_m(lines[i], a), ds = lane_offset_m(scaled[i], a);
      EXPECT_NEAR(ds - middle, (d - middle) * c, 1e-9);
      EXPECT_NEAR(geometry::dot(scaled[i].start, u), geometry::dot(lines[i].start, u), 1e-9);
      EXPECT_NEAR(geometry::dot(scaled[i].end, u), geometry::dot(lines[i].end, u), 1e-9);
      // Both ends move the same way: the line stays parallel to the lanes.
      EXPECT_NEAR(geometry::cross(scaled[i].end - scaled[i].start, u), 0, 1e-9);
    }
  }
}

// A rectangle swept along its long side: below scale 1 the n lines' footprints span
// (n - 1) s c + w of the height H, so the coverage is that over H and the bound is closed-form.
TEST(SpacingScaleBounds, MatchesTheClosedFormOnARectangle) {
  const double height = 200;
  const SurveyPlan plan = rectangle_plan(300, height);
  const double s = plan.imaging.line_spacing_m, w = plan.imaging.footprint_across_m;
  const double n = double(plan.drones[0].mission.lines.size());
  ASSERT_GE(n, 3);
  for (double min : {0.99, 0.95, 0.9}) {
    const SpacingScaleBounds b = spacing_scale_bounds(plan, min);
    const double closed = (min * height - w) / ((n - 1) * s);
    EXPECT_NEAR(b.lo, closed, 2e-5) << min;
    EXPECT_EQ(b.hi, 1.0);
    EXPECT_NEAR(b.middle_m, height / 2, 1e-6);
    EXPECT_NEAR(b.lo_covered_fraction, min, 1e-4);
    EXPECT_DOUBLE_EQ(b.nominal_covered_fraction, 1.0);
  }
  // Allowed to widen, the coverage stays whole until the footprints part at w / s > 2.
  ASSERT_GT(w / s, 2.0);
  const SpacingScaleBounds wide = spacing_scale_bounds(plan, 0.99, 0.5, 2.0);
  EXPECT_EQ(wide.hi, 2.0);
  EXPECT_DOUBLE_EQ(wide.hi_covered_fraction, 1.0);
}

// On a real field, the lowest scale still covers the minimum by an independent sampling of the
// footprints, and a little lower does not.
TEST(SpacingScaleBounds, TheLowerBoundIsTightByIndependentSampling) {
  const SurveyPlan plan = plan_survey(test::meadow_request(60));
  const double min = 0.97;
  const SpacingScaleBounds b = spacing_scale_bounds(plan, min);
  ASSERT_LT(b.lo, 1.0);
  ASSERT_GT(b.lo, 0.5);
  auto sampled = [&](double scale) {
    return test::sample_coverage(plan.area,
                                 scale_line_spacing(plan.drones[0].mission.lines,
                                                    plan.sweep.angle_deg, b.middle_m, scale),
                                 plan.imaging.footprint_across_m, 800)
        .fraction();
  };
  EXPECT_NEAR(sampled(b.lo), min, 2e-3);
  EXPECT_LT(sampled(b.lo - 0.02), min);
  EXPECT_GT(sampled(1.0), 0.999);
}

TEST(SpacingScaleBounds, APlanBelowTheMinimumKeepsItsSpacing) {
  const SurveyPlan plan = rectangle_plan(300, 200);
  SurveyPlan shrunk = plan;  // lines closed in to half their spacing: the edges stay unseen
  shrunk.drones[0].mission.lines =
      scale_line_spacing(plan.drones[0].mission.lines, plan.sweep.angle_deg, 100, 0.5);
  const SpacingScaleBounds b = spacing_scale_bounds(shrunk, 0.999);
  EXPECT_LT(b.nominal_covered_fraction, 0.999);
  EXPECT_EQ(b.lo, 1.0);
  EXPECT_EQ(b.hi, 1.0);
  EXPECT_THROW(spacing_scale_bounds(plan, 0.0), std::invalid_argument);
  EXPECT_THROW(spacing_scale_bounds(plan, 1.5), std::invalid_argument);
}

}  // namespace
}  // namespace swath::planning
