// The dynamic task graph (docs/swath-fleet.md): sync nodes as awaits form them, dtg.json, and the
// graph as a value for the forecaster.

#include "runtime/runtime_impl.hpp"

namespace swath::fleet::rt {

int Runtime::dtg_sync_node(Task& t) {
  if (t.sync_node < 0 || t.issued_since_sync) {
    t.sync_node = static_cast<int>(syncs_.size());
    t.issued_since_sync = false;
    syncs_.push_back({t.id, now_, {}});
    dtg_changed_ = true;
  }
  return t.sync_node;
}

// dtg.json: task nodes, sync nodes, edges (docs/swath-fleet.md).
std::string Runtime::dtg_json() const {
  auto id = [](const DtgRef& r) { return (r.sync ? "s" : "t") + std::to_string(r.number); };
  json nodes = json::array();
  for (const Task& t : tasks_) {
    json n{{"id", "t" + std::to_string(t.id)},
           {"type", "task"},
           {"kind", t.kind},
           {"created_s", round6(t.created_s)},
           {"ended_s", round6(t.ended_s)},
           {"status", t.status == TaskStatus::done        ? "done"
                      : t.status == TaskStatus::cancelled ? "cancelled"
                                                          : "failed"},
           {"actions", t.actions.size()},
           {"drones", t.drones_used},
           {"ended_seq", t.ended_seq},
           {"same_drone", t.flags.same_drone},
           {"interruptible", t.flags.interruptible}};
    json script = json::array();
    for (const ScriptStep& st : t.script) {
      static const char* const kActs[] = {"fly_to", "sense", "hover", "custom", "fly_sensing"};
      json step;
      switch (st.op) {
        case ScriptStep::act:
          step["act"] = kActs[st.act_type];
          if (st.act_type == 0 || st.act_type == 4) step["to"] = {st.to.x, st.to.y, st.to.z};
          if (st.act_type == 1 || st.act_type == 4) step["sensor"] = st.name;
          if (st.act_type == 3) step["name"] = st.name;
          if (st.act_type == 2 || st.act_type == 3) step["s"] = st.s;
          if (st.act_type == 4) step["period_s"] = st.s;
          break;
        case ScriptStep::await: {
          json refs = json::array();
          for (int r : st.refs)
            refs.push_back(r >= 0 ? "t" + std::to_string(r) : "a" + std::to_string(-r - 1));
          step["await"] = std::move(refs);
          if (st.any) step["any"] = true;
          break;
        }
        case ScriptStep::spawn:
          step["spawn"] = "t" + std::to_string(st.refs.front());
          break;
        case ScriptStep::cancel:
          step["cancel"] = "t" + std::to_string(st.refs.front());
          break;
        case ScriptStep::delay:
          step["delay_s"] = st.s;
          break;
      }
      if (st.raised) step["raised"] = true;
      step["seq"] = st.seq;
      script.push_back(std::move(step));
    }
    n["script"] = std::move(script);
    if (t.first_loc)
      n["first_loc"] = {round6(t.first_loc->x), round6(t.first_loc->y), round6(t.first_loc->z)};
    nodes.push_back(std::move(n));
  }
  for (std::size_t k = 0; k < syncs_.size(); ++k)
    nodes.push_back(json{{"id", "s" + std::to_string(k)},
                         {"type", "sync"},
                         {"waiter", syncs_[k].waiter},
                         {"created_s", round6(syncs_[k].created_s)},
                         {"awaited", syncs_[k].awaited}});
  json edges = json::array();
  for (const Edge& e : edges_)
    edges.push_back(json{{"from", id(e.from)},
                         {"to", id(e.to)},
                         {"type", e.type == DtgEdgeType::spawn  ? "spawn"
                                  : e.type == DtgEdgeType::sync ? "sync"
                                                                : "cancel"}});
  return json{{"app", settings_.app_name},
              {"seed", settings_.seed},
              {"nodes", nodes},
              {"edges", edges}}
             .dump(1) +
         "\n";
}

// The DTG as it stands now, as a value (the forecaster's input): tasks still running are its
// frontier. Node indices as parse_dtg makes them: tasks by id, then sync nodes by number.
Dtg Runtime::live_dtg() const {
  Dtg g;
  g.app = settings_.app_name;
  g.nodes.reserve(tasks_.size() + syncs_.size());
  for (const Task& t : tasks_) {
    DtgNode n;
    n.number = t.id;
    n.kind = t.kind;
    n.created_s = round6(t.created_s);
    if (t.status != TaskStatus::running) {
      n.ended_s = round6(t.ended_s);
      n.status = t.status == TaskStatus::done        ? DtgStatus::done
                 : t.status == TaskStatus::cancelled ? DtgStatus::cancelled
                                                     : DtgStatus::failed;
    }
    if (t.first_loc)
      n.first_loc_m = Vec3{round6(t.first_loc->x), round6(t.first_loc->y), round6(t.first_loc->z)};
    g.nodes.push_back(std::move(n));
  }
  for (std::size_t k = 0; k < syncs_.size(); ++k) {
    DtgNode n;
    n.type = DtgNodeType::sync;
    n.number = static_cast<int>(k);
    n.waiter = syncs_[k].waiter;
    n.kind = tasks_[static_cast<std::size_t>(n.waiter)].kind;
    n.created_s = round6(syncs_[k].created_s);
    g.nodes.push_back(std::move(n));
  }
  const int tasks = static_cast<int>(tasks_.size());
  auto index = [&](const DtgRef& r) { return r.sync ? tasks + r.number : r.number; };
  for (const Edge& e : edges_) g.edges.push_back({index(e.from), index(e.to), e.type});
  return g;
}

}  // namespace swath::fleet::rt
