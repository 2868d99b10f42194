// Stops beside zones, as swath plan's own check reads the written files (docs/safety-notes.md,
// "Stopping margin"): a property test over random fields with a pond or a strip near the default
// home, at random speeds, with and without the DJI KMZ twin. Every plan is written as swath plan
// writes it (survey_files) and checked as swath plan checks it (preflight::verify_files with the
// plan's zones and clearance): no stop may overrun into a zone's clearance band. Plans the
// planner refuses are counted apart; the check may refuse none for a stop's overrun.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "local_field.hpp"
#include "swath/base/input_error.hpp"
#include "swath/planning/plan_features.hpp"
#include "swath/planning/survey.hpp"
#include "swath/planning/survey_files.hpp"
#include "swath/preflight/verify.hpp"

namespace swath::planning {
namespace {

using geometry::GeoPoint;
using geometry::Point2;
using geometry::Ring;

using Rng = std::mt19937_64;

double uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

Ring rectangle(Point2 centre, double angle_rad, double length_m, double width_m) {
  const Point2 u{std::cos(angle_rad), std::sin(angle_rad)}, v{-u.y, u.x};
  const Point2 a = u * (length_m / 2), b = v * (width_m / 2);
  return {centre - a - b, centre + a - b, centre + a + b, centre - a + b};
}

// A round pond of `n` vertices.
Ring pond(Point2 centre, double radius_m, int n) {
  Ring ring;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n;
    ring.push_back(centre + Point2{std::cos(a), std::sin(a)} * radius_m);
  }
  return ring;
}

struct Layout {
  SurveyRequest request;
  bool dji = false;
  std::string what;
};

// A quadrilateral field of 150-300 m, no home given (the default home: its south-west-most vertex
// clear of the zones), and either a pond inside it (a hole) or a strip at a random angle passing
// the default home's vertex a little beyond the clearance (within the overrun at the speed).
Layout random_layout(Rng& rng) {
  Layout l;
  const double w = uniform(rng, 150, 300), h = uniform(rng, 150, 300);
  Ring outer = {{0, 0},
                {w, uniform(rng, -40, 40)},
                {w + uniform(rng, -40, 40), h},
                {uniform(rng, -40, 40), h + uniform(rng, -20, 20)}};
  const double speed_m_s = uniform(rng, 3, 12);
  const double clearance_m = uniform(rng, 3, 12);
  const double overrun_m = speed_m_s * speed_m_s / 5;
  l.dji = rng() % 2 == 0;
  std::vector<Ring> holes;
  std::vector<Ring> zones;
  if (rng() % 2 == 0) {
    const double r = uniform(rng, 15, 35);
    holes.push_back(pond({uniform(rng, 0.35, 0.65) * w, uniform(rng, 0.35, 0.65) * h}, r, 12));
    l.what = "pond";
  } else {
    // A strip west of the vertex at (0, 0), its near edge the clearance and up to the overrun
    // more from it, running 40 degrees either side of north (past the field, or cutting it).
    const double angle = M_PI / 2 + uniform(rng, -0.7, 0.7);
    const Point2 west{-std::sin(angle), std::cos(angle)};  // across the strip, away from (0, 0)
    const double width_m = uniform(rng, 8, 20);
    const double gap_m = clearance_m + uniform(rng, 0.2, overrun_m + 1);
    zones.push_back(rectangle(west * (gap_m + width_m / 2), angle, 3000, width_m));
    l.what = "strip";
  }
  l.request.field = test::local_field({outer, holes});
  const geometry::LocalFrame& frame = *l.request.field.frame;
  for (const Ring& z : zones) {
    std::vector<GeoPoint> g;
    for (const Point2& p : z) g.push_back(frame.to_geo(p));
    l.request.exclusions.push_back(g);
  }
  l.request.camera = {"test", 17.3, 13.0, 12.29, 5280, 3956, std::nullopt};
  PhotogrammetryMode m;
  m.altitude_m = 30;
  l.request.mode = m;
  l.request.clearance_m = clearance_m;
  l.request.speed_m_s = speed_m_s;
  if (l.dji) l.request.slowest_approach_m_s = 1.0;  // swath plan --dji
  char text[120];
  std::snprintf(text, sizeof text, "%s, %.2f m/s, clearance %.2f m%s", l.what.c_str(), speed_m_s,
                clearance_m, l.dji ? ", --dji" : "");
  l.what = text;
  return l;
}

// swath plan's check of its files (PlanCommand::check_options): the zones as given, the lined
// area, the clearance.
preflight::CheckOptions check_options(const SurveyPlan& plan) {
  preflight::CheckOptions options;
  for (std::size_t k = 0; k < plan.no_fly_geo.size(); ++k)
    options.zones.push_back({no_fly_name(plan, k), plan.no_fly_geo[k]});
  options.area = lined_area(plan);
  options.clearance_m = plan.request.clearance_m;
  return options;
}

// How far short of the clearance a stop's overrun may still come in a written file, metres: the
// limits docs/safety-notes.md gives ("0.01 m short": a stop on the clearance band's edge that
// cannot be moved), and, with the DJI twin, DJI's waypoint spacing (a point closer than 0.51 m to
// the one before it is merged into it, turning the leg into the next stop by a fraction of a
// degree: 5 to 9 cm on 3 of these layouts). Before the home's stop was approached slowly and the
// KMZ's hovers read as holds, 17 of these 60 layouts were refused, up to 9.21 m short or inside
// the zone.
constexpr double kStopShortAtMost_m = 0.1;

TEST(PlannedStops, DefaultHomesAndPondsPassThePlansOwnCheck) {
  Rng rng(1818);
  int written = 0, planner_refused = 0, overruns = 0, other = 0;
  double worst_m = 0.0;
  const int n = 60;
  for (int k = 0; k < n; ++k) {
    const Layout l = random_layout(rng);
    SCOPED_TRACE("layout " + std::to_string(k) + ": " + l.what);
    SurveyPlan plan;
    std::vector<std::pair<std::string, std::string>> files;
    try {
      plan = plan_survey(l.request);
      FileOptions options;
      options.dji = l.dji;
      files = survey_files(plan, options);
    } catch (const base::InputError& e) {
      ++planner_refused;
      std::printf("layout %d (%s) refused by the planner: %s\n", k, l.what.c_str(), e.what());
      continue;
    }
    const preflight::Report report = preflight::verify_files(files, check_options(plan));
    if (report.ok()) {
      ++written;
      continue;
    }
    // A leg itself within the clearance (a line's end inside a strip's band, no stop's doing:
    // layout 18, 0.73 m, as before) is counted apart; its stops' overruns are not judged.
    bool leg = false;
    for (const preflight::Violation& v : report.violations)
      leg = leg || v.text.find("stopping margin") == std::string::npos;
    if (leg) {
      ++other;
    } else {
      ++overruns;
      for (const preflight::Violation& v : report.violations) {
        worst_m = std::max(worst_m, v.amount);
        EXPECT_LE(v.amount, kStopShortAtMost_m) << v.text;
      }
    }
    std::printf("layout %d (%s) refused by the check: %s\n", k, l.what.c_str(),
                report.violations.front().text.c_str());
    // SWATH_PLANNED_STOPS_DIR=DIR: a refused layout's files in DIR/K/ (to look at one).
    if (const char* dir = std::getenv("SWATH_PLANNED_STOPS_DIR")) {
      const std::filesystem::path out = std::filesystem::path(dir) / std::to_string(k);
      std::filesystem::create_directories(out);
      for (const auto& [name, bytes] : files) std::ofstream(out / name, std::ios::binary) << bytes;
    }
  }
  std::printf(
      "planned stops: %d of %d written, %d refused by the planner, %d by the check "
      "(%d for a stop's overrun, at worst %.3f m short)\n",
      written, n, planner_refused, overruns + other, overruns, worst_m);
  // 55 today (4 refused for stops within kStopShortAtMost_m, 1 for a leg 0.73 m inside the
  // clearance of a strip); 43 before.
  EXPECT_GE(written, 54);
}

}  // namespace
}  // namespace swath::planning
