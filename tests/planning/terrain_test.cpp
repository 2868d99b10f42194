// Terrain following without a raster (terrain.hpp): the profile simplification against a brute
// check on random profiles, and a flat ground that must change nothing but the frames' facts.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "meadow_survey.hpp"
#include "swath/planning/survey.hpp"
#include "swath/planning/terrain.hpp"

namespace swath::planning {
namespace {

TEST(ProfileBreaks, EverySampleIsWithinTheToleranceOfTheKeptLine) {
  std::mt19937 rng(11);
  std::normal_distribution<double> step(0.0, 0.7);
  std::uniform_real_distribution<double> tol(0.1, 3.0);
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t n = 2 + rng() % 400;
    std::vector<double> along(n), h(n);
    double z = 0;
    for (std::size_t k = 0; k < n; ++k) {
      along[k] = 0.8 * static_cast<double>(k);
      h[k] = z += step(rng);
    }
    const double t = tol(rng);
    const std::vector<std::size_t> keep = profile_breaks(along, h, t);
    ASSERT_GE(keep.size(), 2u);
    EXPECT_EQ(keep.front(), 0u);
    EXPECT_EQ(keep.back(), n - 1);
    for (std::size_t q = 0; q + 1 < keep.size(); ++q) {
      const std::size_t a = keep[q], b = keep[q + 1];
      ASSERT_LT(a, b);
      for (std::size_t k = a; k <= b; ++k) {
        const double line = h[a] + (along[k] - along[a]) / (along[b] - along[a]) * (h[b] - h[a]);
        EXPECT_LE(std::abs(h[k] - line), t + 1e-12) << trial;
      }
    }
    // Nothing kept that was not needed at the top level: a straight profile keeps its ends.
    std::vector<double> straight(n);
    for (std::size_t k = 0; k < n; ++k) straight[k] = 3.0 - 0.1 * along[k];
    EXPECT_EQ(profile_breaks(along, straight, t).size(), 2u);
  }
}

// A flat ground 432 m above sea level, with data everywhere.
class Flat final : public geometry::Ground {
 public:
  std::vector<double> heights_m(const std::vector<geometry::GeoPoint>& p) const override {
    return std::vector<double>(p.size(), 432.0);
  }
  double resolution_m() const override { return 1.0; }
  std::string source() const override { return "flat"; }
};

TEST(TerrainFollowing, FlatGroundChangesNoWaypointAndGivesTheAltitudesAboveSeaLevel) {
  SurveyRequest r = test::meadow_request(80);
  const SurveyPlan plain = plan_survey(r);
  r.terrain = TerrainRequest{std::make_shared<Flat>(), 1.0, AltitudeFrame::amsl};
  const SurveyPlan flat = plan_survey(r);
  ASSERT_TRUE(flat.terrain);
  EXPECT_EQ(flat.terrain->waypoints_added, 0u);
  EXPECT_DOUBLE_EQ(flat.terrain->agl_min_m, 80.0);
  EXPECT_DOUBLE_EQ(flat.terrain->agl_max_m, 80.0);
  EXPECT_DOUBLE_EQ(flat.terrain->climb_max_m_s, 0.0);
  const auto& a = plain.drones.at(0).mission.items;
  const auto& b = flat.drones.at(0).mission.items;
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].kind, b[k].kind);
    EXPECT_EQ(a[k].position, b[k].position);
    if (!positional(a[k].kind)) continue;
    EXPECT_NEAR(b[k].altitude_m, a[k].altitude_m, 1e-9);
    EXPECT_NEAR(b[k].altitude_amsl_m, 432.0 + a[k].altitude_m, 1e-9);
  }
  EXPECT_EQ(flat.drones[0].mission.home_amsl_m, 432.0);
}

}  // namespace
}  // namespace swath::planning
