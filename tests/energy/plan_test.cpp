#include "swath/energy/plan.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <cmath>

#include "swath/base/input_error.hpp"
#include "swath/energy/expression.hpp"

namespace swath::energy {
namespace {

const std::string kPlans = std::string(SWATH_SOURCE_DIR) + "/plans/";

std::string plan_error_of(const std::string& text) {
  try {
    parse_plan(text, "p.stages");
  } catch (const base::InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(PlanFile, ThePapersSurveyExample) {
  const Plan p = read_plan(kPlans + "survey.stages");
  ASSERT_EQ(p.stages.size(), 5u);
  EXPECT_EQ(p.trajectory_parameters(), 1u);
  EXPECT_EQ(p.computations(), 2u);
  EXPECT_DOUBLE_EQ(p.stages[0].gain, 0.0003);
  EXPECT_EQ(p.stages[0].direction, 1);
  EXPECT_EQ(p.stages[1].direction, -1);  // rotation 270
  EXPECT_EQ(p.stages[0].trajectory[0], (Interval{-3000, 0}));
  EXPECT_EQ(p.stages[0].computations[1], (Interval{32, 448}));
  EXPECT_EQ(p.stages[4].computations[0],
            (Interval{0, 0}));  // the last stage's computations are off
  EXPECT_EQ(p.stages[0].line, 16);
  // The first triggering point sits on the first circle, for any c1 in its bounds.
  const std::vector<std::string> vars{"x", "y", "c1"};
  for (double c1 : {-3000.0, -1000.0, 0.0}) {
    const double tx = Expression(p.stages[0].trigger_x, vars, "t")({0, 0, c1});
    const double ty = Expression(p.stages[0].trigger_y, vars, "t")({0, 0, c1});
    EXPECT_NEAR(Expression(p.stages[0].phi, vars, "phi")({tx, ty, c1}), 0.0, 1e-9) << c1;
    EXPECT_NEAR(tx, -std::sqrt(4900 + c1) - 45, 1e-12);
  }
}

TEST(PlanFile, YamlAndStageFormatAgreeAndRoundTrip) {
  const Plan stages = read_plan(kPlans + "survey.stages");
  const Plan yaml = read_plan(kPlans + "survey.yaml");
  ASSERT_EQ(stages.stages.size(), yaml.stages.size());
  for (std::size_t k = 0; k < stages.stages.size(); ++k) {
    Stage a = stages.stages[k], b = yaml.stages[k];
    a.line = b.line = 0;
    EXPECT_EQ(a, b) << k;
  }
  const Plan again = parse_plan(format_plan(stages), "again");
  for (std::size_t k = 0; k < stages.stages.size(); ++k) {
    Stage a = stages.stages[k], b = again.stages[k];
    a.line = b.line = 0;
    EXPECT_EQ(a, b) << k;
  }
}

TEST(PlanFile, ErrorsNameTheLineAndTheProblem) {
  const std::string ok_tail = "1, 2\n[0, 1]\n[2, 10]\n";
  EXPECT_NE(plan_error_of("0.1; 90; x+z\n" + ok_tail)
                .find("p.stages: line 1 (phi): unknown variable 'z'"),
            std::string::npos)
      << plan_error_of("0.1; 90; x+z\n" + ok_tail);
  EXPECT_NE(
      plan_error_of("0.1; 90; x\n1, 2\n[1, 0]\n").find("line 3: interval '[1, 0]' has lo > hi"),
      std::string::npos);
  EXPECT_NE(plan_error_of("0.1; 90; x\n1, 2\n[1 0]\n").find("line 3: '[1 0]' is not an interval"),
            std::string::npos);
  EXPECT_NE(plan_error_of("0.1; 90; x\n[0, 1]\n").find("line 1: the stage has no triggering point"),
            std::string::npos);
  EXPECT_NE(plan_error_of("0.1; 90; x\n" + ok_tail + "0.1; 90; y\n1, 2\n[0, 1]\n")
                .find("line 5: stage 2 has 0 computation lines, stage 1 has 1"),
            std::string::npos);
  EXPECT_NE(plan_error_of("0.1; 45; x\n" + ok_tail).find("rotation '45' must be 0 or 90"),
            std::string::npos);
  EXPECT_NE(plan_error_of("0.1 90 x\n" + ok_tail).find("a stage starts with 'gain; rotation; phi"),
            std::string::npos);
  EXPECT_NE(plan_error_of("# only comments\n").find("the plan has no stage"), std::string::npos);
  EXPECT_NE(plan_error_of("0.1; 90; x+c2\n" + ok_tail).find("unknown variable 'c2'"),
            std::string::npos);
}

TEST(Expression, EvaluatesThePapersFunctions) {
  const Expression e("sqrt(x)+sin(y)^2+cos(y)^2+c1*10^3", {"x", "y", "c1"}, "e");
  EXPECT_NEAR(e({16, 0.7, 0.002}), 4 + 1 + 2, 1e-12);
  const Expression copy = e;
  EXPECT_NEAR(copy({9, 0, 0}), 4, 1e-12);
  EXPECT_DOUBLE_EQ(constant("-3*10^3", "c"), -3000);
  EXPECT_THROW(constant("1/0", "c"), base::InputError);
}

// Stage plans are .stages; a .plan is QGroundControl's: JSON refused naming the command that
// reads it, the stage format read with a warning (the old name).
TEST(Plan, DotPlanIsQgroundcontrolsUnlessItHoldsStages) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "swath-plan-ext";
  std::filesystem::create_directories(dir);
  const std::filesystem::path old_name = dir / "old.plan", qgc = dir / "qgc.plan";
  std::ofstream(old_name) << "0.05; 90; x\n0, 600\n[0, 0]\n";
  std::ofstream(qgc) << "{\"fileType\": \"Plan\", \"mission\": {}}\n";
  std::vector<std::string> warnings;
  EXPECT_EQ(read_plan(old_name, &warnings).stages.size(), 1u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], old_name.string() +
                             ": stage plans are now named .stages (.plan is QGroundControl's); "
                             "read as a stage plan");
  try {
    read_plan(qgc);
    ADD_FAILURE() << "a QGC plan was read as stages";
  } catch (const base::InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              qgc.string() +
                  ": a QGroundControl mission (JSON), not a plan of stages; "
                  "swath-energy budget flies QGC missions, run takes stage plans "
                  "(.stages)");
  }
  warnings.clear();
  read_plan(std::string(SWATH_SOURCE_DIR) + "/plans/survey.stages", &warnings);
  EXPECT_TRUE(warnings.empty());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace swath::energy
