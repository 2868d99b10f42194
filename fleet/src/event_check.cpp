#include "swath/fleet/event_check.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
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
// A field as text, or "" when absent or not a string (a log is checked, never trusted).
std::string text(const json& e, const char* key) {
  const auto it = e.find(key);
  return it != e.end() && it->is_string() ? it->get<std::string>() : std::string();
}
bool flag(const json& e, const char* key) {
  const auto it = e.find(key);
  return it != e.end() && it->is_boolean() && it->get<bool>();
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
    if (ev != "drone_state") close_state_batch();
    check_names(e, ev, drone);
    event(e, ev, drone, id(e, "task"));
    envelope(e, ev, drone);
  }

  EventCheck finish() {
    close_state_batch();
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
    if (e.contains("envelope") && e["envelope"].is_object()) {
      const json& env = e["envelope"];
      ceiling_m_ = number(env, "ceiling_m").value_or(ceiling_m_);
      separation_m_ = number(env, "separation_m").value_or(separation_m_);
      ceiling_m_ = std::min(ceiling_m_, number(env, "fence_max_altitude_m").value_or(ceiling_m_));
      inclusions_ = rings(env, "inclusions");
      exclusions_ = rings(env, "exclusions");
    }
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
      if (task) request_visible(*task, id(e, "segment").value_or(-1));
    } else if (ev == "position") {
      if (drone && lost_.count(*drone)) bad(n_, "R8", "a lost drone was sent to a forecast place");
    } else if (ev == "relief") {
      if (drone && lost_.count(*drone)) bad(n_, "R8", "a lost drone was sent to stand by");
    } else if (ev == "dispatch") {
      if (drone && lost_.count(*drone)) bad(n_, "R8", "a lost drone was dispatched");
      const long long segment = id(e, "segment").value_or(-1);
      if (task && !visible_.count({*task, segment}))
        bad(n_, "R9", "dispatch of a segment never made visible");
      else if (task && segment != latest_segment_[*task])
        bad(n_, "R9",
            "dispatch of task " + std::to_string(*task) + "'s segment " + std::to_string(segment) +
                " while its segment " + std::to_string(latest_segment_[*task]) + " is the one due");
      if (task && drone) same_drone(*task, *drone, "dispatched to");
    } else if (ev == "fault") {
      ++out_.faults;
      if (drone && text(e, "fault") == "motor_failure") lost_.insert(*drone);
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
    if (flag(e, "same_drone")) same_drone_tasks_.insert(*task);
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
    if (task && id(e, "drone")) {
      same_drone(*task, *id(e, "drone"), "a result from");
      if (same_drone_tasks_.count(*task) && !bound_.count(*task)) bound_[*task] = *id(e, "drone");
    }
    if (!task || !action) return;
    if (!delivered_.insert({*task, *action}).second)
      bad(n_, "R5",
          "the result of task " + std::to_string(*task) + " action " + std::to_string(*action) +
              " delivered twice");
    else if (last_action_.count(*task) && *action <= last_action_[*task])
      bad(n_, "R5", "task " + std::to_string(*task) + "'s results out of order");
    last_action_[*task] = std::max(last_action_.count(*task) ? last_action_[*task] : -1, *action);
  }

  // R9: a task's segments are announced in order; a requeued one again under its index.
  void request_visible(long long task, long long segment) {
    const auto it = latest_segment_.find(task);
    const long long expected = it == latest_segment_.end() ? 0 : it->second + 1;
    if (segment != expected && (it == latest_segment_.end() || segment != it->second))
      bad(n_, "R9",
          "task " + std::to_string(task) + "'s segment " + std::to_string(segment) +
              " announced after segment " +
              (it == latest_segment_.end() ? std::string("none") : std::to_string(it->second)));
    latest_segment_[task] = segment;
    visible_.insert({task, segment});
  }

  // R10: a same_drone task stays on the drone of its first result.
  void same_drone(long long task, long long drone, const char* what) {
    const auto it = bound_.find(task);
    if (it != bound_.end() && it->second != drone)
      bad(n_, "R10",
          "same_drone task " + std::to_string(task) + " " + what + " drone " +
              std::to_string(drone) + ", bound to drone " + std::to_string(it->second));
  }

  static std::vector<std::vector<std::array<double, 2>>> rings(const json& env, const char* key) {
    std::vector<std::vector<std::array<double, 2>>> out;
    if (!env.contains(key) || !env[key].is_array()) return out;
    for (const json& r : env[key]) {
      std::vector<std::array<double, 2>> ring;
      if (r.is_array())
        for (const json& p : r)
          if (p.is_array() && p.size() >= 2 && p[0].is_number() && p[1].is_number())
            ring.push_back({p[0].get<double>(), p[1].get<double>()});
      if (ring.size() >= 3) out.push_back(std::move(ring));
    }
    return out;
  }
  // Even-odd rule; a point on an edge counts as inside (the checker's own, not geometry's).
  static bool inside(const std::vector<std::array<double, 2>>& ring, double x, double y) {
    bool in = false;
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
      const auto& a = ring[i];
      const auto& b = ring[j];
      const double cross = (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
      if (std::abs(cross) < 1e-9 && x >= std::min(a[0], b[0]) - 1e-9 &&
          x <= std::max(a[0], b[0]) + 1e-9 && y >= std::min(a[1], b[1]) - 1e-9 &&
          y <= std::max(a[1], b[1]) + 1e-9)
        return true;
      if ((a[1] > y) != (b[1] > y) && x < (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]) + a[0])
        in = !in;
    }
    return in;
  }

  // R11–R13 for the positions an event carries: drones' (drone_state, drone_mode) and targets
  // (dispatch, a forecast place's position, a stand-by's relief).
  void envelope(const json& e, const std::string& ev, std::optional<long long> drone) {
    const bool target = ev == "dispatch" || ev == "position" || ev == "relief";
    if (ev != "drone_state" && ev != "drone_mode" && !target) return;
    const auto x = number(e, "x_m"), y = number(e, "y_m"), z = number(e, "alt_m");
    if (!x || !y || !z) return;
    const std::string who = ev == "dispatch"   ? "a dispatch target"
                            : ev == "position" ? "a forecast place"
                            : ev == "relief"   ? "a stand-by place"
                                               : "drone " + std::to_string(drone.value_or(-1));
    if (!target) out_.max_altitude_m = std::max(out_.max_altitude_m, *z);
    if (*z > ceiling_m_ + 1e-6)
      bad(n_, "R12",
          who + " at " + std::to_string(*z) + " m, above the ceiling of " +
              std::to_string(ceiling_m_) + " m");
    const std::string refusal = fence_refusal(*x, *y);
    if (!refusal.empty()) bad(n_, "R13", who + " " + refusal);
    if (!target && drone) leg_from_last(*drone, {*x, *y, *z}, refusal.empty(), e);
    if (ev == "drone_state" && drone) {
      const auto t = number(e, "t_s").value_or(-1);
      if (t != batch_t_) close_state_batch();
      batch_t_ = t;
      if (*z > 0 && text(e, "state") != "lost") batch_.push_back({*x, *y, *z});
    }
  }

  // "" when (x, y) is inside the inclusion fence and outside every exclusion, else why not.
  std::string fence_refusal(double x, double y) const {
    bool in = inclusions_.empty();
    for (const auto& r : inclusions_) in = in || inside(r, x, y);
    if (!in) return "outside the inclusion fence";
    for (const auto& r : exclusions_)
      if (inside(r, x, y)) return "inside an exclusion fence";
    return "";
  }

  // Where (0..1) the segment a-b crosses or touches the rings' edges.
  std::vector<double> crossings(
      const std::array<double, 3>& a, const std::array<double, 3>& b,
      const std::vector<std::vector<std::array<double, 2>>>& rings) const {
    std::vector<double> out;
    const double dx = b[0] - a[0], dy = b[1] - a[1];
    for (const auto& ring : rings)
      for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
        const double ex = ring[i][0] - ring[j][0], ey = ring[i][1] - ring[j][1];
        const double den = dx * ey - dy * ex;
        if (std::abs(den) < 1e-12) continue;  // parallel: its ends are other edges' crossings
        const double wx = ring[j][0] - a[0], wy = ring[j][1] - a[1];
        const double t = (wx * ey - wy * ex) / den, u = (wx * dy - wy * dx) / den;
        if (t > 0 && t < 1 && u >= -1e-12 && u <= 1 + 1e-12) out.push_back(t);
      }
    return out;
  }

  // R13 between two logged positions of a drone in flight: the straight leg between them (what
  // the drone flies between samples) judged piece by piece, split where it crosses a fence edge,
  // so a leg across a strip narrower than a second's flight is seen. Its height is linear along
  // the leg, so the ceiling (R12) holds on it when it holds at both ends.
  void leg_from_last(long long drone, const std::array<double, 3>& p, bool p_inside,
                     const json& e) {
    const bool lost = text(e, "state") == "lost";
    const auto it = last_position_.find(drone);
    if (it != last_position_.end() && it->second.inside && p_inside && !lost) {
      const auto& a = it->second.at;
      std::vector<double> ts = crossings(a, p, inclusions_);
      const auto more = crossings(a, p, exclusions_);
      ts.insert(ts.end(), more.begin(), more.end());
      ts.push_back(0);
      ts.push_back(1);
      std::sort(ts.begin(), ts.end());
      for (std::size_t k = 1; k < ts.size(); ++k) {
        if (ts[k] - ts[k - 1] < 1e-9) continue;
        const double m = (ts[k] + ts[k - 1]) / 2;
        const std::string why = fence_refusal(a[0] + m * (p[0] - a[0]), a[1] + m * (p[1] - a[1]));
        if (why.empty()) continue;
        bad(n_, "R13",
            "drone " + std::to_string(drone) + "'s leg from (" + std::to_string(a[0]) + ", " +
                std::to_string(a[1]) + ") to (" + std::to_string(p[0]) + ", " +
                std::to_string(p[1]) + ") m passes " + why);
        break;
      }
    }
    last_position_[drone] = {p, p_inside && !lost};
  }

  // R11: the airborne drones of one drone_state time, pairwise.
  void close_state_batch() {
    for (std::size_t i = 0; i < batch_.size(); ++i)
      for (std::size_t j = 0; j < i; ++j) {
        const double d = std::hypot(batch_[i][0] - batch_[j][0], batch_[i][1] - batch_[j][1],
                                    batch_[i][2] - batch_[j][2]);
        out_.least_separation_m = std::min(out_.least_separation_m, d);
        if (d < separation_m_ - 1e-6)
          bad(n_, "R11",
              "two airborne drones " + std::to_string(d) + " m apart at t " +
                  std::to_string(batch_t_) + " s (separation " + std::to_string(separation_m_) +
                  " m)");
      }
    batch_.clear();
    batch_t_ = -1;
  }

  EventCheck out_;
  int n_ = 0;
  double ceiling_m_ = 120, separation_m_ = 5;
  std::vector<std::vector<std::array<double, 2>>> inclusions_, exclusions_;
  std::vector<std::array<double, 3>> batch_;  // airborne drones at batch_t_
  struct Logged {
    std::array<double, 3> at;
    bool inside;  // inside the fence and not lost: a leg from it is judged
  };
  std::map<long long, Logged> last_position_;  // drone → its last logged position
  double batch_t_ = -1;
  std::map<long long, long long> latest_segment_, bound_;  // task → segment; same_drone → drone
  std::set<long long> same_drone_tasks_;
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
