#pragma once
// Plans of flight stages (paper 004 Appendix II, docs/swath-energy.md), in the stage format or
// YAML.

#include <filesystem>
#include <string>
#include <vector>

namespace swath::energy {

struct Interval {
  double lo = 0.0, hi = 0.0;  ///< lo <= hi; [0, 0] switches a computation off
  friend bool operator==(const Interval&, const Interval&) = default;
};

struct Stage {
  int line = 0;       ///< the stage's first line in its file (0 for YAML)
  double gain = 0.0;  ///< k_e of the guidance field
  int direction = 1;  ///< +1 counter-clockwise (rotation 0 or 90), -1 clockwise (1 or 270)
  std::string phi;    ///< trajectory phi(x, y, c1, ..), zero on the path
  std::string trigger_x, trigger_y;    ///< the triggering point, may use c1, ..
  std::vector<Interval> trajectory;    ///< bounds of c1, c2, .. (one line, one or more intervals)
  std::vector<Interval> computations;  ///< bounds of each computation parameter, one line each
  friend bool operator==(const Stage&, const Stage&) = default;
};

struct Plan {
  std::string source;
  std::vector<Stage> stages;
  std::size_t trajectory_parameters() const {
    return stages.empty() ? 0 : stages[0].trajectory.size();
  }
  std::size_t computations() const { return stages.empty() ? 0 : stages[0].computations.size(); }
};

/// Parses the stage format: per stage a line "gain; rotation; phi", a line "x, y" (the triggering
/// point), a line of trajectory bounds "[lo, hi]" (several for several parameters), then one
/// "[lo, hi]" line per computation. '#' starts a comment; blank lines are ignored; numbers and
/// bounds may be expressions ("-3*10^3"). Every stage has the same numbers of trajectory parameters
/// and computations. Expressions are compiled to check them. Throws base::InputError naming the
/// file, the line and the problem (unknown variable, bad interval, lo > hi, missing trigger,
/// inconsistent number of computation lines, bad rotation).
Plan parse_plan(const std::string& text, const std::string& source);

/// The same plan as YAML:
///   stages:
///     - {gain: 0.0003, rotation: 90, phi: "(x+45)^2+(y-146)^2-4900+c1",
///        trigger: ["-sqrt(4900+c1)-45", "146"], trajectory: [[-3000, 0]], computations: [[2, 10],
///        [32, 448]]}
Plan parse_plan_yaml(const std::string& text, const std::string& source);

/// By extension: .yaml/.yml as YAML, anything else (.stages) the stage format. A `.plan` file is
/// what QGroundControl writes: one that is JSON is refused with the command that reads it
/// (swath-energy budget); one in the stage format (the old name of .stages) is read, with a
/// warning added to `warnings` when given.
Plan read_plan(const std::filesystem::path& path, std::vector<std::string>* warnings = nullptr);

/// The plan in the stage format (parse_plan() reads it back to an equal plan).
std::string format_plan(const Plan& plan);

}  // namespace swath::energy
