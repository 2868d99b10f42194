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

// One pass over the log: a line at a time, each rule where its facts are at hand.
class Checker {
 public:
  void line(const std::string& raw) {
    ++n_;
    out_.lines = n_;
    json e;
    try {
      e = json::parse(raw);
    } catch (const json::exception&) {
      bad(n_, "R1", "not a JSON object");
      return;
    }
    if (!e.is_object() || !e.contains("ev") || !e["ev"].is_string()) {
      bad(n_, "R1", "no \"ev\"");
      return;
    }
    const std::string ev = e["ev"];
    check_time(e, ev);
    if (ev == "run_start") return run_start(e);
    if (ev == "run_end") return run_end(e);
    const auto drone = id(e, "drone");
    check_names(e, ev, drone);
    event(e, ev, drone, id(e, "task"));
  }

  EventCheck finish() {
    if (n_ == 0)
      bad(0, "R1", "no events");
    else if (!ended_)
      bad(n_, "R1", "the last event is not run_end");
    for (const auto& [task, line] : created_at_)
      if (!ended_at_.count(task)) bad(line, "R3", "task " + std::to_string(task) + " never ends");
    return std::move(out_);
  }

 private:
  void bad(int line, const char* rule, std::string what) {
    if (out_.violations.size() < 1000) out_.violations.push_back({line, rule, std::move(what)});
  }

  // R1: times present, finite, never going back; run_start first, nothing after run_end.
  void check_time(const json& e, const std::string& ev) {
    const auto t = number(e, "t_s");
    if (!t || !std::isfinite(*t) || *t < 0) {
      bad(n_, "R1", "no finite t_s ≥ 0");
    } else {
      if (*t < last_t_ - 1e-9) bad(n_, "R1", "time goes back");
      last_t_ = std::max(last_t_, *t);
    }
    if (ended_) bad(n_, "R1", "an event after run_end");
    if (n_ == 1 && ev != "run_start") bad(n_, "R1", "the first event is not run_start");
  }

  void run_start(const json& e) {
    if (started_) bad(n_, "R1", "a second run_start");
    started_ = true;
    if (const auto m = number(e, "max_time_s")) max_time_ = *m;
    if (e.contains("drones") && e["drones"].is_array())
      for (const auto& d : e["drones"]) {
        if (const auto i = id(d, "drone")) drones_.insert(*i);
        if (const auto soc = number(d, "soc"); soc && (*soc < 0 || *soc > 1 + 1e-9))
          bad(n_, "R6", "state of charge outside [0, 1]");
      }
  }

  void run_end(const json& e) {
    ended_ = true;
    if (const auto t = number(e, "t_s"); t && *t > max_time_ + 1e-9)
      bad(n_, "R7", "the run ends after max_time_s");
  }

  // R8: drones named exist; R6: charge in [0, 1]; R2/R4: tasks named between creation and end.
  void check_names(const json& e, const std::string& ev, std::optional<long long> drone) {
    if (drone && !drones_.count(*drone))
      bad(n_, "R8", "drone " + std::to_string(*drone) + " is not in the fleet");
    if (const auto soc = number(e, "soc"); soc && (*soc < 0 || *soc > 1 + 1e-9))
      bad(n_, "R6", "state of charge outside [0, 1]");
    const auto task = id(e, "task");
    if (!task || ev == "task_created") return;
    if (!created_at_.count(*task))
      bad(n_, "R2", "task " + std::to_string(*task) + " named before it was created");
    if (ended_at_.count(*task) && ev != "duplicate_result")
      bad(n_, "R4", "task " + std::to_string(*task) + " named after it ended");
  }

  void event(const json& e, const std::string& ev, std::optional<long long> drone,
             std::optional<long long> task) {
    if (ev == "task_created") {
      task_created(e, task);
    } else if (ev == "task_done" || ev == "task_cancelled" || ev == "task_failed") {
      task_ended(ev, task);
    } else if (ev == "action_done") {
      action_done(e, task);
    } else if (ev == "duplicate_result") {
      ++out_.duplicates;
    } else if (ev == "request_visible") {
      if (task) visible_.insert({*task, id(e, "segment").value_or(-1)});
    } else if (ev == "position") {
      if (drone && lost_.count(*drone)) bad(n_, "R8", "a lost drone was sent to a forecast place");
    } else if (ev == "relief") {
      if (drone && lost_.count(*drone)) bad(n_, "R8", "a lost drone was sent to stand by");
    } else if (ev == "dispatch") {
      if (drone && lost_.count(*drone)) bad(n_, "R8", "a lost drone was dispatched");
      if (task && !visible_.count({*task, id(e, "segment").value_or(-1)}))
        bad(n_, "R9", "dispatch of a segment never made visible");
    } else if (ev == "fault") {
      ++out_.faults;
      if (drone && e.value("fault", "") == "motor_failure") lost_.insert(*drone);
    }
  }

  void task_created(const json& e, std::optional<long long> task) {
    if (!task) {
      bad(n_, "R2", "task_created without a task id");
      return;
    }
    if (created_at_.count(*task)) bad(n_, "R2", "task " + std::to_string(*task) + " created twice");
    created_at_[*task] = n_;
    ++out_.tasks;
    const auto parent = id(e, "parent");
    if (parent && *parent >= 0 && !created_at_.count(*parent))
      bad(n_, "R2", "its parent " + std::to_string(*parent) + " was not created before");
  }

  // R3: every task ends once.
  void task_ended(const std::string& ev, std::optional<long long> task) {
    ++out_.terminal[ev];
    if (!task) return;
    if (ended_at_.count(*task))
      bad(n_, "R3",
          "task " + std::to_string(*task) + " ends a second time (first on line " +
              std::to_string(ended_at_[*task]) + ")");
    else
      ended_at_[*task] = n_;
  }

  // R5: every result delivered at most once, in order.
  void action_done(const json& e, std::optional<long long> task) {
    ++out_.results;
    const auto action = id(e, "action");
    if (!task || !action) return;
    if (!delivered_.insert({*task, *action}).second)
      bad(n_, "R5",
          "the result of task " + std::to_string(*task) + " action " + std::to_string(*action) +
              " delivered twice");
    else if (last_action_.count(*task) && *action <= last_action_[*task])
      bad(n_, "R5", "task " + std::to_string(*task) + "'s results out of order");
    last_action_[*task] = std::max(last_action_.count(*task) ? last_action_[*task] : -1, *action);
  }

  EventCheck out_;
  int n_ = 0;
  double last_t_ = 0, max_time_ = std::numeric_limits<double>::infinity();
  bool started_ = false, ended_ = false;
  std::set<long long> drones_, lost_;
  std::map<long long, int> created_at_, ended_at_;  // task → line
  std::map<long long, long long> last_action_;      // task → last delivered action
  std::set<std::pair<long long, long long>> delivered_, visible_;
};

}  // namespace

EventCheck check_events(const std::string& text) {
  Checker c;
  std::istringstream in(text);
  for (std::string raw; std::getline(in, raw);) c.line(raw);
  return c.finish();
}

}  // namespace swath::fleet
