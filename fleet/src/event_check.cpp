#include "swath/fleet/event_check.hpp"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

namespace swath::fleet {
namespace {

using json = nlohmann::json;

// A field as an integer id, or nullopt when absent or not an integer.
std::optional<long long> id(const json& e, const char* key) {
  const auto it = e.find(key);
  if (it == e.end() || !it->is_number_integer()) return std::nullopt;
  return it->get<long long>();
}
std::optional<double> number(const json& e, const char* key) {
  const auto it = e.find(key);
  if (it == e.end() || !it->is_number()) return std::nullopt;
  return it->get<double>();
}

}  // namespace

EventCheck check_events(const std::string& text) {
  EventCheck out;
  auto bad = [&](int line, const char* rule, std::string what) {
    if (out.violations.size() < 1000) out.violations.push_back({line, rule, std::move(what)});
  };
  std::istringstream in(text);
  std::string raw;
  double last_t = 0, max_time = std::numeric_limits<double>::infinity();
  bool started = false, ended = false;
  std::set<long long> drones, lost;
  std::map<long long, int> created_at, ended_at;  // task → line
  std::map<long long, long long> last_action;     // task → last delivered action
  std::set<std::pair<long long, long long>> delivered, visible;
  int n = 0;
  while (std::getline(in, raw)) {
    ++n;
    out.lines = n;
    json e;
    try {
      e = json::parse(raw);
    } catch (const json::exception&) {
      bad(n, "R1", "not a JSON object");
      continue;
    }
    if (!e.is_object() || !e.contains("ev") || !e["ev"].is_string()) {
      bad(n, "R1", "no \"ev\"");
      continue;
    }
    const std::string ev = e["ev"];
    const auto t = number(e, "t_s");
    if (!t || !std::isfinite(*t) || *t < 0) {
      bad(n, "R1", "no finite t_s ≥ 0");
    } else {
      if (*t < last_t - 1e-9) bad(n, "R1", "time goes back");
      last_t = std::max(last_t, *t);
    }
    if (ended) bad(n, "R1", "an event after run_end");
    if (n == 1 && ev != "run_start") bad(n, "R1", "the first event is not run_start");
    if (ev == "run_start") {
      if (started) bad(n, "R1", "a second run_start");
      started = true;
      if (const auto m = number(e, "max_time_s")) max_time = *m;
      if (e.contains("drones") && e["drones"].is_array())
        for (const auto& d : e["drones"]) {
          if (const auto i = id(d, "drone")) drones.insert(*i);
          if (const auto soc = number(d, "soc"); soc && (*soc < 0 || *soc > 1 + 1e-9))
            bad(n, "R6", "state of charge outside [0, 1]");
        }
      continue;
    }
    if (ev == "run_end") {
      ended = true;
      if (t && *t > max_time + 1e-9) bad(n, "R7", "the run ends after max_time_s");
      continue;
    }
    // Drones named must exist; a lost drone neither flies nor acts.
    const auto drone = id(e, "drone");
    if (drone && !drones.count(*drone))
      bad(n, "R8", "drone " + std::to_string(*drone) + " is not in the fleet");
    if (const auto soc = number(e, "soc"); soc && (*soc < 0 || *soc > 1 + 1e-9))
      bad(n, "R6", "state of charge outside [0, 1]");
    const auto task = id(e, "task");
    const bool names_task = task.has_value() && ev != "task_created";
    if (names_task) {
      if (!created_at.count(*task))
        bad(n, "R2", "task " + std::to_string(*task) + " named before it was created");
      if (ended_at.count(*task) && ev != "duplicate_result")
        bad(n, "R4", "task " + std::to_string(*task) + " named after it ended");
    }
    if (ev == "task_created") {
      if (!task) {
        bad(n, "R2", "task_created without a task id");
        continue;
      }
      if (created_at.count(*task)) bad(n, "R2", "task " + std::to_string(*task) + " created twice");
      created_at[*task] = n;
      ++out.tasks;
      const auto parent = id(e, "parent");
      if (parent && *parent >= 0 && !created_at.count(*parent))
        bad(n, "R2", "its parent " + std::to_string(*parent) + " was not created before");
    } else if (ev == "task_done" || ev == "task_cancelled" || ev == "task_failed") {
      ++out.terminal[ev];
      if (task) {
        if (ended_at.count(*task))
          bad(n, "R3",
              "task " + std::to_string(*task) + " ends a second time (first on line " +
                  std::to_string(ended_at[*task]) + ")");
        else
          ended_at[*task] = n;
      }
    } else if (ev == "action_done") {
      ++out.results;
      const auto action = id(e, "action");
      if (task && action) {
        if (!delivered.insert({*task, *action}).second)
          bad(n, "R5",
              "the result of task " + std::to_string(*task) + " action " + std::to_string(*action) +
                  " delivered twice");
        else if (last_action.count(*task) && *action <= last_action[*task])
          bad(n, "R5", "task " + std::to_string(*task) + "'s results out of order");
        last_action[*task] = std::max(last_action.count(*task) ? last_action[*task] : -1, *action);
      }
    } else if (ev == "duplicate_result") {
      ++out.duplicates;
    } else if (ev == "request_visible") {
      if (task) visible.insert({*task, id(e, "segment").value_or(-1)});
    } else if (ev == "position") {
      if (drone && lost.count(*drone)) bad(n, "R8", "a lost drone was sent to a forecast place");
    } else if (ev == "relief") {
      if (drone && lost.count(*drone)) bad(n, "R8", "a lost drone was sent to stand by");
    } else if (ev == "dispatch") {
      if (drone && lost.count(*drone)) bad(n, "R8", "a lost drone was dispatched");
      if (task && !visible.count({*task, id(e, "segment").value_or(-1)}))
        bad(n, "R9", "dispatch of a segment never made visible");
    } else if (ev == "fault") {
      ++out.faults;
      if (drone && e.value("fault", "") == "motor_failure") lost.insert(*drone);
    }
  }
  if (n == 0)
    bad(0, "R1", "no events");
  else if (!ended)
    bad(n, "R1", "the last event is not run_end");
  for (const auto& [task, line] : created_at)
    if (!ended_at.count(task)) bad(line, "R3", "task " + std::to_string(task) + " never ends");
  return out;
}

}  // namespace swath::fleet
