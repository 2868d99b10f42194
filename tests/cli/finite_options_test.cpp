// No option of swath's takes NaN or an infinity: CLI11 reads "nan" and "inf" as doubles and a
// range check (x < lo || x > hi) lets NaN through, so every program refuses them after parsing,
// before the command runs (apps/common/program.cpp), alone or inside a pair such as LAT,LON.
#include <gtest/gtest.h>

#include <string>

#include "cli_runner.hpp"

namespace swath::test {
namespace {

void expect_refused(const CliRun& r, const std::string& option) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(option), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("not a finite number"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST(FiniteOptions, NanAndInfinitiesAreRefusedByEveryProgram) {
  const std::string dir = fresh_dir("finite-options");
  const std::string plan = "plan share/fields/meadow.geojson --camera sony-ilce-qx1 -o " + dir;
  expect_refused(run_swath(plan + " --altitude nan"), "--altitude");
  expect_refused(run_swath(plan + " --altitude 60 --speed -Infinity"), "--speed");
  expect_refused(run_swath(plan + " --altitude 60 --home NaN,8.54"), "--home");
  expect_refused(run_swath_fleet("run road --world road --max-time nan -o " + dir), "--max-time");
  expect_refused(run_swath_control("fit --p-run nan x.csv"), "--p-run");
}

}  // namespace
}  // namespace swath::test
