// A run's record from its events (event_replay.hpp).
#include "swath/fleet/event_replay.hpp"

#include <nlohmann/json.hpp>
#include <sstream>

#include "swath/base/input_error.hpp"

namespace swath::fleet {
namespace {

using json = nlohmann::json;

struct Open {
  std::string mode;
  double since = 0;
};

}  // namespace

RunRecord replay_record(const std::string& events_jsonl, const std::string& source) {
  RunRecord r;
  std::vector<Open> open;
  std::istringstream in(events_jsonl);
  std::string raw;
  int n = 0;
  bool started = false, ended = false;
  while (std::getline(in, raw)) {
    ++n;
    const std::string where = source + ": line " + std::to_string(n) + ": ";
    json e;
    try {
      e = json::parse(raw);
    } catch (const json::exception&) {
      throw base::InputError(where + "not a JSON event");
    }
    try {
      const std::string ev = e.at("ev");
      const double t = e.at("t_s");
      auto drone = [&]() -> DroneRecord& {
        const int i = e.at("drone");
        if (i < 0 || static_cast<std::size_t>(i) >= r.drones.size())
          throw base::InputError(where + "drone " + std::to_string(i) + " is not run_start's");
        return r.drones[static_cast<std::size_t>(i)];
      };
      if (ev == "run_start") {
        started = true;
        for (const json& d : e.at("drones")) {
          r.drones.emplace_back();
          r.drones.back().name = d.at("name");
        }
        open.assign(r.drones.size(), {});
      } else if (!started) {
        throw base::InputError(where + "an event before run_start");
      } else if (ev == "drone_state") {
        drone().track.push_back({t, e.at("x_m"), e.at("y_m"), e.at("alt_m")});
      } else if (ev == "drone_mode") {
        DroneRecord& d = drone();
        const double at = e.at("at_s");
        const std::string state = e.at("state");
        d.track.push_back({at, e.at("x_m"), e.at("y_m"), e.at("alt_m")});
        Open& o = open[static_cast<std::size_t>(e.at("drone").get<int>())];
        if (state != o.mode) {  // as the runtime closes a span
          if (!o.mode.empty() && at > o.since) d.spans.push_back({o.since, at, o.mode});
          o = {state, at};
        }
      } else if (ev == "action_done" && e.contains("at_s")) {
        r.served.push_back({e.at("at_s"), e.at("x_m"), e.at("y_m")});
      } else if (ev == "request_cancelled") {
        r.cancelled.push_back({t, e.at("x_m"), e.at("y_m")});
      } else if (ev == "run_end") {
        ended = true;
        r.end_s = t;
        r.completed = e.at("completed");
        for (std::size_t i = 0; i < open.size(); ++i)
          if (!open[i].mode.empty() && t > open[i].since)
            r.drones[i].spans.push_back({open[i].since, t, open[i].mode});
      }
    } catch (const json::exception& x) {
      throw base::InputError(where + "an event without the fields it needs (" +
                             std::string(x.what()).substr(0, 80) + ")");
    }
  }
  if (!ended) throw base::InputError(source + ": no run_end (the run's log is incomplete)");
  return r;
}

}  // namespace swath::fleet
