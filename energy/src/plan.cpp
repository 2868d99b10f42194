#include "swath/energy/plan.hpp"
#include "swath/base/file_text.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/yaml_map.hpp"
#include "swath/energy/expression.hpp"

namespace swath::energy {
namespace {

using base::InputError;

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

// Top-level comma split (commas inside parentheses belong to function arguments).
std::vector<std::string> split_top(const std::string& s, char sep) {
  std::vector<std::string> parts(1);
  int depth = 0;
  for (char ch : s) {
    if (ch == '(' || ch == '[') ++depth;
    if (ch == ')' || ch == ']') --depth;
    if (ch == sep && depth == 0) {
      parts.emplace_back();
    } else {
      parts.back() += ch;
    }
  }
  for (auto& p : parts) p = trim(p);
  return parts;
}

// "[a, b]" or "[a, b], [c, d]" -> intervals.
std::vector<Interval> intervals(const std::string& text, const std::string& where) {
  std::vector<Interval> out;
  for (const std::string& part : split_top(text, ',')) {
    if (part.size() < 2 || part.front() != '[' || part.back() != ']')
      throw InputError(where + ": '" + text + "' is not an interval [lo, hi]");
    const auto ends = split_top(part.substr(1, part.size() - 2), ',');
    if (ends.size() != 2) throw InputError(where + ": '" + part + "' is not an interval [lo, hi]");
    const Interval iv{constant(ends[0], where), constant(ends[1], where)};
    if (iv.lo > iv.hi) throw InputError(where + ": interval '" + part + "' has lo > hi");
    out.push_back(iv);
  }
  return out;
}

int direction_of(const std::string& text, const std::string& where) {
  const double r = constant(text, where);
  if (r == 0 || r == 90) return 1;
  if (r == 1 || r == 270) return -1;
  throw InputError(where + ": rotation '" + text +
                   "' must be 0 or 90 (counter-clockwise), 1 or 270 (clockwise)");
}

std::vector<std::string> variables(std::size_t parameters) {
  std::vector<std::string> v{"x", "y"};
  for (std::size_t i = 1; i <= parameters; ++i) {
    std::string name = "c";
    name += std::to_string(i);
    v.push_back(name);
  }
  return v;
}

// Compiles every expression of every stage (unknown variables, syntax) and checks the counts.
void check(const Plan& plan) {
  if (plan.stages.empty()) throw InputError(plan.source + ": the plan has no stage");
  const Stage& first = plan.stages.front();
  for (std::size_t k = 0; k < plan.stages.size(); ++k) {
    const Stage& s = plan.stages[k];
    const std::string where = plan.source + (s.line > 0 ? ": line " + std::to_string(s.line)
                                                        : ": stage " + std::to_string(k + 1));
    if (s.computations.size() != first.computations.size())
      throw InputError(where + ": stage " + std::to_string(k + 1) + " has " +
                       std::to_string(s.computations.size()) + " computation lines, stage 1 has " +
                       std::to_string(first.computations.size()));
    if (s.trajectory.size() != first.trajectory.size())
      throw InputError(where + ": stage " + std::to_string(k + 1) + " bounds " +
                       std::to_string(s.trajectory.size()) +
                       " trajectory parameters, stage 1 bounds " +
                       std::to_string(first.trajectory.size()));
    const auto vars = variables(s.trajectory.size());
    Expression(s.phi, vars, where + " (phi)");
    Expression(s.trigger_x, vars, where + " (trigger x)");
    Expression(s.trigger_y, vars, where + " (trigger y)");
    if (!std::isfinite(s.gain) || s.gain <= 0) throw InputError(where + ": the gain must be > 0");
  }
}

}  // namespace

Plan parse_plan(const std::string& text, const std::string& source) {
  struct Line {
    int number;
    std::string text;
  };
  std::vector<Line> lines;
  std::istringstream in(text);
  std::string raw;
  for (int n = 1; std::getline(in, raw); ++n) {
    const std::string t = trim(raw.substr(0, raw.find('#')));
    if (!t.empty()) lines.push_back({n, t});
  }
  Plan plan;
  plan.source = source;
  std::size_t i = 0;
  while (i < lines.size()) {
    const std::string where = source + ": line " + std::to_string(lines[i].number);
    const auto head = split_top(lines[i].text, ';');
    if (head.size() != 3)
      throw InputError(where +
                       ": a stage starts with 'gain; rotation; phi(x, y, c1..)' (three "
                       "fields separated by ';')");
    Stage stage;
    stage.line = lines[i].number;
    stage.gain = constant(head[0], where + " (gain)");
    stage.direction = direction_of(head[1], where);
    stage.phi = head[2];
    ++i;
    if (i >= lines.size() || lines[i].text.find(';') != std::string::npos ||
        lines[i].text.front() == '[')
      throw InputError(where + ": the stage has no triggering point 'x, y' on the next line");
    const auto trigger = split_top(lines[i].text, ',');
    if (trigger.size() != 2)
      throw InputError(source + ": line " + std::to_string(lines[i].number) +
                       ": the triggering point must be 'x, y'");
    stage.trigger_x = trigger[0];
    stage.trigger_y = trigger[1];
    ++i;
    if (i >= lines.size() || lines[i].text.front() != '[')
      throw InputError(
          where + ": the stage has no trajectory bounds '[lo, hi]' after its triggering point");
    stage.trajectory =
        intervals(lines[i].text, source + ": line " + std::to_string(lines[i].number));
    ++i;
    while (i < lines.size() && lines[i].text.front() == '[') {
      const auto iv =
          intervals(lines[i].text, source + ": line " + std::to_string(lines[i].number));
      if (iv.size() != 1)
        throw InputError(source + ": line " + std::to_string(lines[i].number) +
                         ": one interval per computation line");
      stage.computations.push_back(iv[0]);
      ++i;
    }
    plan.stages.push_back(std::move(stage));
  }
  check(plan);
  return plan;
}

namespace {

Plan plan_from_yaml(const std::string& text, const std::string& source) {
  const YAML::Node root = base::load_yaml(text, source);
  if (!root.IsMap() || !root["stages"] || !root["stages"].IsSequence())
    throw InputError(source + ": a YAML plan is a mapping with a list 'stages'");
  Plan plan;
  plan.source = source;
  for (const YAML::Node& n : root["stages"]) {
    const std::string where = source + ": line " + std::to_string(n.Mark().line + 1);
    if (!n.IsMap())
      throw InputError(where + ": a stage is a mapping {gain, rotation, phi, trigger, ..}");
    base::check_plain_unique_keys(n, source);
    auto field = [&](const char* key) {
      if (!n[key]) throw InputError(where + ": the stage has no '" + std::string(key) + "'");
      return n[key].as<std::string>();
    };
    Stage s;
    s.gain = constant(field("gain"), where + " (gain)");
    s.direction = direction_of(field("rotation"), where);
    s.phi = field("phi");
    if (!n["trigger"] || !n["trigger"].IsSequence() || n["trigger"].size() != 2)
      throw InputError(where + ": the stage has no triggering point 'trigger: [x, y]'");
    s.trigger_x = n["trigger"][0].as<std::string>();
    s.trigger_y = n["trigger"][1].as<std::string>();
    auto bounds = [&](const char* key) {
      std::vector<Interval> out;
      if (!n[key]) return out;
      for (const YAML::Node& b : n[key]) {
        if (!b.IsSequence() || b.size() != 2)
          throw InputError(where + ": " + key + " holds intervals [lo, hi]");
        const Interval iv{constant(b[0].as<std::string>(), where),
                          constant(b[1].as<std::string>(), where)};
        if (iv.lo > iv.hi) throw InputError(where + ": an interval of " + key + " has lo > hi");
        out.push_back(iv);
      }
      return out;
    };
    s.trajectory = bounds("trajectory");
    s.computations = bounds("computations");
    plan.stages.push_back(std::move(s));
  }
  check(plan);
  return plan;
}

}  // namespace

Plan parse_plan_yaml(const std::string& text, const std::string& source) {
  return base::yaml_guard(source, [&] { return plan_from_yaml(text, source); });
}

Plan read_plan(const std::filesystem::path& path, std::vector<std::string>* warnings) {
  const std::string text = base::read_text_file(path, "plan file");
  const std::string ext = path.extension().string();
  if (ext == ".plan") {
    const std::size_t first = text.find_first_not_of(" \t\r\n");
    if (first != std::string::npos && text[first] == '{')
      throw InputError(path.string() +
                       ": a QGroundControl mission (JSON), not a plan of stages; swath-energy "
                       "budget flies QGC missions, run takes stage plans (.stages)");
    if (warnings)
      warnings->push_back(path.string() +
                          ": stage plans are now named .stages (.plan is QGroundControl's); read "
                          "as a stage plan");
  }
  return ext == ".yaml" || ext == ".yml" ? parse_plan_yaml(text, path.string())
                                         : parse_plan(text, path.string());
}

std::string format_plan(const Plan& plan) {
  std::ostringstream out;
  auto interval = [&](const Interval& iv) {
    out << '[' << base::shortest_text(iv.lo) << ", " << base::shortest_text(iv.hi) << ']';
  };
  for (const Stage& s : plan.stages) {
    out << base::shortest_text(s.gain) << "; " << (s.direction > 0 ? 90 : 270) << "; " << s.phi
        << '\n';
    out << s.trigger_x << ", " << s.trigger_y << '\n';
    for (std::size_t i = 0; i < s.trajectory.size(); ++i) {
      if (i > 0) out << ", ";
      interval(s.trajectory[i]);
    }
    out << '\n';
    for (const Interval& c : s.computations) {
      interval(c);
      out << '\n';
    }
  }
  return out.str();
}

}  // namespace swath::energy
