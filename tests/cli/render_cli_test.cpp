// Pictures: `swath plan --render` and `swath render DIR`, checked on the decoded PNG.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "../../apps/swath/coverage_image.hpp"
#include "cli_runner.hpp"
#include "swath/geometry/local_frame.hpp"

namespace swath::test {
namespace {

TEST(RenderCli, CoverageImageHasTheSizeAScaleBarAsLongAsItClaimsAndIsRedrawnIdentically) {
  const std::string out = fresh_dir("render");
  const CliRun run = run_swath(
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 --render --size "
      "800x600 -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string png = read_text(out + "/coverage.png");
  const render::Image image = render::decode_png(png);
  EXPECT_EQ(image.width, 800);
  EXPECT_EQ(image.height, 600);
  // Where the picture says the bar is and how many metres it claims; then its pixels.
  const apps::CoverageImage planned = apps::coverage_image(
      planning::parse_mission_geojson(read_text(out + "/mission.geojson"), "mission.geojson"),
      planning::parse_plan_figures(read_text(out + "/summary.json"), "summary.json"), 800, 600);
  EXPECT_GT(planned.scale_bar_m, 0);
  EXPECT_NEAR(planned.scale_bar_px, planned.scale_bar_m * planned.view.px_per_m, 1e-9);
  const int row = static_cast<int>(planned.scale_bar_start_px.y);
  int dark = 0;
  for (int x = 0; x < image.width / 2; ++x) dark += image.at(x, row, 0) < 100;
  EXPECT_NEAR(dark, planned.scale_bar_px, 2.0);
  // Outside the field (left edge, mid height): white.
  EXPECT_EQ(image.at(3, 300, 0), 255);
  // `swath render DIR` draws the same picture.
  const std::string again = out + "/again.png";
  const CliRun redraw = run_swath("render " + out + " --coverage " + again + " --size 800x600");
  ASSERT_EQ(redraw.exit_code, 0) << redraw.err;
  EXPECT_EQ(read_text(again), png);
}

// A pilot's picture at the smallest common size: the legend measured and inside, clear of the
// title and the map; no-fly zones, each drone's own home, and where the lines start and end drawn.
TEST(RenderCli, LegendInsideAndClearOfTitleAndMapWithZonesHomesAndEnds) {
  struct Case {
    std::string args;
    int width, height;
  };
  const std::vector<Case> cases{
      {"plan share/fields/vineyard.kml --camera dji-phantom-4-pro --altitude 60 --home "
       "46.2276,7.5917",
       640, 480},
      {"plan share/fields/vineyard.kml --camera dji-phantom-4-pro --altitude 60 --home "
       "46.2276,7.5917",
       1600, 1200},
      {"plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 --fleet "
       "share/fleets/three-quads.yaml --division region",
       640, 480},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args + " " + std::to_string(c.width));
    const std::string out = fresh_dir("legend");
    const std::string size = std::to_string(c.width) + "x" + std::to_string(c.height);
    const CliRun run = run_swath(c.args + " --render --size " + size + " -o " + out);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const render::Image image = render::decode_png(read_text(out + "/coverage.png"));
    const planning::PlanFeatures features =
        planning::parse_mission_geojson(read_text(out + "/mission.geojson"), "mission.geojson");
    const apps::CoverageImage planned = apps::coverage_image(
        features, planning::parse_plan_figures(read_text(out + "/summary.json"), "summary.json"),
        c.width, c.height);
    EXPECT_TRUE(planned.legend_box.inside(c.width, c.height));
    EXPECT_TRUE(planned.title_box.inside(c.width, c.height));
    EXPECT_FALSE(planned.legend_box.overlaps(planned.title_box));
    EXPECT_GT(planned.legend_box.right_px - planned.legend_box.left_px, 100);
    // Every label's measured text inside the image.
    for (const render::Label& l : planned.scene.labels) {
      const render::TextExtent e = render::text_extent(l.text, l.height_px);
      EXPECT_GE(l.x_px, 0) << l.text;
      EXPECT_LE(l.x_px + e.width_px, c.width) << l.text;
      EXPECT_GE(l.y_px - e.height_px, 0) << l.text;
      EXPECT_LE(l.y_px + e.baseline_px, c.height) << l.text;
    }
    // The map (area, homes) clear of the legend: every area vertex and home outside its box.
    const geometry::LocalFrame frame(features.area.front().front());
    auto pixel = [&](const geometry::GeoPoint& g) {
      return planned.view.to_pixel(frame.to_local(g));
    };
    auto outside_legend = [&](geometry::Point2 p) {
      return !planned.legend_box.overlaps({p.x - 1, p.y - 1, p.x + 1, p.y + 1});
    };
    for (const auto& ring : features.area)
      for (const auto& g : ring) EXPECT_TRUE(outside_legend(pixel(g)));
    EXPECT_TRUE(outside_legend(pixel(features.home)));
    // The legend's backing box: light just inside its right edge.
    const int bx = static_cast<int>(planned.legend_box.right_px) - 3;
    const int by = static_cast<int>((planned.legend_box.top_px + planned.legend_box.bottom_px) / 2);
    EXPECT_GT(image.at(bx, by, 0), 200);
    // A no-fly zone is red where nothing else is drawn: its centre (the pond is convex enough).
    bool has_zone_entry = false;
    for (const render::Label& l : planned.scene.labels) has_zone_entry |= l.text == "no-fly zone";
    EXPECT_EQ(has_zone_entry, !features.no_fly.empty());
    // The first line's start: the drone's colour inside a dark ring.
    for (const auto& sw : features.sweeps) {
      if (sw.line != 0) continue;
      const geometry::Point2 p = pixel(sw.start);
      const int x = static_cast<int>(std::lround(p.x)), y = static_cast<int>(std::lround(p.y));
      const int r = image.at(x, y, 0), g = image.at(x, y, 1), b = image.at(x, y, 2);
      EXPECT_GT(std::max({r, g, b}) - std::min({r, g, b}), 80) << "drone " << sw.drone;
    }
    // Each drone's own home, in its colour (charlie: orange).
    for (const auto& h : features.drone_homes) {
      const geometry::Point2 p = pixel(h.at);
      const int x = static_cast<int>(std::lround(p.x)), y = static_cast<int>(std::lround(p.y)) + 2;
      if (h.drone == 3) {
        EXPECT_GT(image.at(x, y, 0), 200);
        EXPECT_LT(image.at(x, y, 2), 80);
      }
    }
  }
}

TEST(RenderCli, NotAPlanIsAClearError) {
  const CliRun run = run_swath("render share/fields");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(
      run.err.find("share/fields/mission.geojson: cannot open (is this a swath plan directory?)"),
      std::string::npos)
      << run.err;
  const CliRun size = run_swath(
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 --render --size 10x10 "
      "-o " +
      fresh_dir("small"));
  EXPECT_EQ(size.exit_code, 2);
  EXPECT_NE(size.err.find("--size '10x10'"), std::string::npos) << size.err;
}

// `swath render DIR` never replaces a file of the user's in the plan's directory named as one it
// writes there (coverage.png, plan.html): refused naming it, exit 2, nothing written (the page
// not either); a picture it drew before is replaced, and a file named with --coverage is written
// as asked.
TEST(RenderCli, AFileSwathDidNotWriteIsNeverReplaced) {
  namespace fs = std::filesystem;
  const std::string out = fresh_dir("render-users-file");
  ASSERT_EQ(
      run_swath("plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 60 -o " + out)
          .exit_code,
      0);
  const std::string mine = "MY OWN PICTURE\n";
  std::ofstream(out + "/coverage.png") << mine;
  std::map<std::string, std::string> before = directory_files(out);
  const CliRun picture = run_swath("render " + out + " --html --paths " + out + "/paths.png");
  EXPECT_EQ(picture.exit_code, 2);
  EXPECT_EQ(picture.err, "swath render: " + out +
                             "/coverage.png: a file swath did not write (no .swath-plan.files "
                             "here lists it) would be replaced; move it, or give --coverage "
                             "another file\n");
  EXPECT_EQ(directory_files(out), before) << "neither the page nor the paths are written";
  fs::rename(out + "/coverage.png", out + "/mine.png");
  std::ofstream(out + "/plan.html") << mine;
  before = directory_files(out);
  const CliRun page = run_swath("render " + out + " --html --coverage " + out + "/coverage.png");
  EXPECT_EQ(page.exit_code, 2);
  EXPECT_EQ(page.err, "swath render: " + out +
                          "/plan.html: a file swath did not write (no .swath-plan.files here "
                          "lists it) would be replaced; move it\n");
  EXPECT_EQ(directory_files(out), before) << "the picture is not drawn either";
  fs::remove(out + "/plan.html");
  for (const int width : {500, 400}) {  // the second replaces the first's picture
    const CliRun drawn = run_swath("render " + out + " --size " + std::to_string(width) + "x300");
    ASSERT_EQ(drawn.exit_code, 0) << drawn.err;
    EXPECT_EQ(render::decode_png(read_text(out + "/coverage.png")).width, width);
  }
  const CliRun named = run_swath("render " + out + " --coverage " + out + "/mine.png");
  ASSERT_EQ(named.exit_code, 0) << named.err;
  EXPECT_EQ(render::decode_png(read_text(out + "/mine.png")).width, 1600);
}

}  // namespace
}  // namespace swath::test

namespace swath::test {
namespace {

// The drawing stack (the rasteriser, OpenCV's core and imgproc, libpng) is a module opened on the
// first picture: a plan without --render never loads it (start-up in milliseconds), one with
// --render does, and it brings neither OpenGL nor OpenCV's image codecs (with the GDAL they load).
// The dynamic loader's own trace (LD_DEBUG=files) says which libraries a process opened.
TEST(RenderModule, LoadedOnlyWhenAProgramDraws) {
  const std::string plan = std::string("LD_DEBUG=files '") + SWATH_BINARY +
                           "' plan share/fields/meadow.geojson --camera sony-ilce-qx1 "
                           "--altitude 60 -o ";
  const CliRun quiet = run_program("env", plan + fresh_dir("module-no-render"));
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.err.find("libOSMesa"), std::string::npos);
  EXPECT_EQ(quiet.err.find("libopencv"), std::string::npos);
  EXPECT_EQ(quiet.err.find("libswath_draw"), std::string::npos);

  const CliRun drawn = run_program("env", plan + fresh_dir("module-render") + " --render");
  ASSERT_EQ(drawn.exit_code, 0) << drawn.err;
  EXPECT_NE(drawn.err.find("libswath_draw"), std::string::npos);
  EXPECT_NE(drawn.err.find("libpng16"), std::string::npos);
  EXPECT_EQ(drawn.err.find("libOSMesa"), std::string::npos);
  EXPECT_EQ(drawn.err.find("libopencv_imgcodecs"), std::string::npos);
}

}  // namespace
}  // namespace swath::test
