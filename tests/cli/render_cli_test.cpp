// Pictures: `swath plan --render` and `swath render DIR`, checked on the decoded PNG.
#include <gtest/gtest.h>

#include <filesystem>

#include "../../apps/swath/coverage_image.hpp"
#include "cli_runner.hpp"

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

}  // namespace
}  // namespace swath::test

namespace swath::test {
namespace {

// The drawing stack (OpenGL, OpenCV and the GDAL its codecs bring) is a module opened on the first
// picture: a plan without --render never loads it (start-up in milliseconds), one with --render
// does. The dynamic loader's own trace (LD_DEBUG=files) says which libraries a process opened.
TEST(RenderModule, LoadedOnlyWhenAProgramDraws) {
  const std::string plan = std::string("LD_DEBUG=files '") + SWATH_BINARY +
                           "' plan share/fields/meadow.geojson --camera sony-ilce-qx1 "
                           "--altitude 60 -o ";
  const CliRun quiet = run_program("env", plan + fresh_dir("module-no-render"));
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.err.find("libOSMesa"), std::string::npos);
  EXPECT_EQ(quiet.err.find("libopencv"), std::string::npos);
  EXPECT_EQ(quiet.err.find("libswath_render_gl"), std::string::npos);

  const CliRun drawn = run_program("env", plan + fresh_dir("module-render") + " --render");
  ASSERT_EQ(drawn.exit_code, 0) << drawn.err;
  EXPECT_NE(drawn.err.find("libswath_render_gl"), std::string::npos);
  EXPECT_NE(drawn.err.find("libOSMesa"), std::string::npos);
}

}  // namespace
}  // namespace swath::test
