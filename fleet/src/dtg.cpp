#include "swath/fleet/dtg.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"

namespace swath::fleet {

using base::InputError;
using base::json_array;
using base::json_find;
using base::json_integer;
using base::json_member;
using base::json_number;
using base::json_string;

Dtg Dtg::as_of(double t_s) const {
  Dtg out;
  out.app = app;
  std::vector<int> index(nodes.size(), -1);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!(nodes[i].created_s <= t_s)) continue;
    // Every field but the script (its indices name nodes of the whole graph), copied without it:
    // the forecasters' scoring calls this once per batch.
    const DtgNode& m = nodes[i];
    DtgNode n;
    n.type = m.type;
    n.number = m.number;
    n.kind = m.kind;
    n.created_s = m.created_s;
    n.ended_s = m.ended_s;
    n.status = m.status;
    n.first_loc_m = m.first_loc_m;
    n.waiter = m.waiter;
    n.same_drone = m.same_drone;
    n.interruptible = m.interruptible;
    if (n.type == DtgNodeType::task && !(n.ended_s <= t_s)) {
      n.status = DtgStatus::running;
      n.ended_s = std::numeric_limits<double>::infinity();
    }
    index[i] = static_cast<int>(out.nodes.size());
    out.nodes.push_back(std::move(n));
  }
  for (DtgNode& n : out.nodes)
    if (n.waiter >= 0) n.waiter = index[static_cast<std::size_t>(n.waiter)];
  for (const DtgEdge& e : edges) {
    const int from = index[static_cast<std::size_t>(e.from)];
    const int to = index[static_cast<std::size_t>(e.to)];
    if (from < 0 || to < 0) continue;
    if (e.type == DtgEdgeType::cancel && !(nodes[static_cast<std::size_t>(e.to)].ended_s <= t_s))
      continue;
    out.edges.push_back({from, to, e.type});
  }
  return out;
}

namespace {

DtgStatus status_of(const std::string& s, const std::string& where) {
  if (s == "done") return DtgStatus::done;
  if (s == "cancelled") return DtgStatus::cancelled;
  if (s == "failed") return DtgStatus::failed;
  if (s == "running") return DtgStatus::running;
  throw InputError(where + ": status \"" + s + "\" is none of done, cancelled, failed, running");
}

DtgEdgeType edge_type_of(const std::string& s, const std::string& where) {
  if (s == "spawn") return DtgEdgeType::spawn;
  if (s == "sync") return DtgEdgeType::sync;
  if (s == "cancel") return DtgEdgeType::cancel;
  throw InputError(where + ": edge type \"" + s + "\" is none of spawn, sync, cancel");
}

// "t12" / "s3": the node's type and number.
std::pair<DtgNodeType, int> parse_id(const std::string& id, const std::string& where) {
  const bool ok = id.size() >= 2 && id.size() <= 10 && (id[0] == 't' || id[0] == 's') &&
                  id.find_first_not_of("0123456789", 1) == std::string::npos;
  if (!ok) throw InputError(where + ": node id \"" + id + "\" is not t<number> or s<number>");
  return {id[0] == 't' ? DtgNodeType::task : DtgNodeType::sync, std::stoi(id.substr(1))};
}

vehicle::Vec3 parse_vec3(const nlohmann::json& j, const std::string& where) {
  const auto& a = json_array(j, where, 3);
  return {json_number(a[0], where + "[0]"), json_number(a[1], where + "[1]"),
          json_number(a[2], where + "[2]")};
}

// One script step; `task_index` maps a task id to its node index (-1: none).
DtgStep parse_step(const nlohmann::json& j, const std::string& where,
                   const std::map<std::pair<int, int>, int>& index) {
  if (!j.is_object()) throw InputError(where + ": a script step is an object");
  DtgStep s;
  auto task_ref = [&](const nlohmann::json& r, const std::string& at) {
    const auto [type, number] = parse_id(json_string(r, at), at);
    const auto it = index.find({0, number});
    if (type != DtgNodeType::task || it == index.end())
      throw InputError(at + ": names no task node");
    return it->second;
  };
  auto seconds = [&](const char* key) {
    const double v = json_number(json_member(j, key, where), where + ": " + key);
    if (!(v >= 0 && v <= 1e9)) throw InputError(where + ": " + key + ": not in [0, 1e9] s");
    return v;
  };
  if (const auto* a = json_find(j, "act")) {
    static const char* const kOps[] = {"fly_to", "sense", "hover", "custom", "fly_sensing"};
    const std::string& op = json_string(*a, where + ": act");
    s.action = -1;
    for (int k = 0; k < 5; ++k)
      if (op == kOps[k]) s.action = k;
    if (s.action < 0)
      throw InputError(where + ": act \"" + op +
                       "\" is none of fly_to, sense, hover, custom, fly_sensing");
    if (s.action == 0 || s.action == 4)
      s.to_m = parse_vec3(json_member(j, "to", where), where + ": to");
    if (s.action == 1 || s.action == 4)
      s.name = json_string(json_member(j, "sensor", where), where + ": sensor");
    if (s.action == 3) s.name = json_string(json_member(j, "name", where), where + ": name");
    if (s.action == 2 || s.action == 3) s.seconds = seconds("s");
    if (s.action == 4) {
      s.seconds = seconds("period_s");
      if (!(s.seconds > 0)) throw InputError(where + ": period_s: must be > 0");
    }
  } else if (const auto* aw = json_find(j, "await")) {
    s.op = DtgStep::Op::await;
    const auto& refs = json_array(*aw, where + ": await");
    for (std::size_t k = 0; k < refs.size(); ++k) {
      const std::string at = where + ": await[" + std::to_string(k) + "]";
      const std::string& r = json_string(refs[k], at);
      if (!r.empty() && r[0] == 'a' && r.size() <= 10 &&
          r.find_first_not_of("0123456789", 1) == std::string::npos && r.size() >= 2)
        s.actions.push_back(std::stoi(r.substr(1)));
      else
        s.tasks.push_back(task_ref(refs[k], at));
    }
    if (const auto* any = json_find(j, "any")) {
      if (!any->is_boolean()) throw InputError(where + ": any: expected true or false");
      s.any = any->get<bool>();
    }
  } else if (const auto* sp = json_find(j, "spawn")) {
    s.op = DtgStep::Op::spawn;
    s.tasks.push_back(task_ref(*sp, where + ": spawn"));
  } else if (const auto* cn = json_find(j, "cancel")) {
    s.op = DtgStep::Op::cancel;
    s.tasks.push_back(task_ref(*cn, where + ": cancel"));
  } else if (json_find(j, "delay_s")) {
    s.op = DtgStep::Op::delay;
    s.seconds = seconds("delay_s");
  } else {
    throw InputError(where + ": a script step is one of act, await, spawn, cancel, delay_s");
  }
  if (const auto* r = json_find(j, "raised")) {
    if (!r->is_boolean()) throw InputError(where + ": raised: expected true or false");
    s.raised = r->get<bool>();
  }
  if (const auto* q = json_find(j, "seq")) s.seq = json_integer(*q, 0, 1LL << 53, where + ": seq");
  return s;
}

DtgNode parse_node(const nlohmann::json& j, const std::string& where) {
  DtgNode n;
  const std::string& id = json_string(json_member(j, "id", where), where + ": id");
  const std::string& type = json_string(json_member(j, "type", where), where + ": type");
  const auto [id_type, number] = parse_id(id, where);
  n.number = number;
  if (type != "task" && type != "sync")
    throw InputError(where + ": node type \"" + type + "\" is neither task nor sync");
  n.type = type == "task" ? DtgNodeType::task : DtgNodeType::sync;
  if (n.type != id_type)
    throw InputError(where + ": a " + type + " node's id \"" + id + "\" names the other type");
  n.created_s = json_number(json_member(j, "created_s", where), where + ": created_s");
  if (n.type == DtgNodeType::sync) {
    n.waiter = static_cast<int>(
        json_integer(json_member(j, "waiter", where), -1, 1'000'000'000, where + ": waiter"));
    return n;
  }
  n.kind = json_string(json_member(j, "kind", where), where + ": kind");
  n.status = status_of(json_string(json_member(j, "status", where), where + ": status"), where);
  const double ended = json_number(json_member(j, "ended_s", where), where + ": ended_s");
  // The runtime writes -1 for a task that never ended (still running when the run stopped).
  if (n.status != DtgStatus::running && ended >= n.created_s)
    n.ended_s = ended;
  else
    n.status = DtgStatus::running;
  if (const auto* q = json_find(j, "ended_seq"))
    n.ended_seq = json_integer(*q, -1, 1LL << 53, where + ": ended_seq");
  if (const auto* f = json_find(j, "same_drone")) {
    if (!f->is_boolean()) throw InputError(where + ": same_drone: expected true or false");
    n.same_drone = f->get<bool>();
  }
  if (const auto* f = json_find(j, "interruptible")) {
    if (!f->is_boolean()) throw InputError(where + ": interruptible: expected true or false");
    n.interruptible = f->get<bool>();
  }
  if (const auto* loc = json_find(j, "first_loc")) {
    const auto& a = json_array(*loc, where + ": first_loc", 3);
    n.first_loc_m = vehicle::Vec3{json_number(a[0], where + ": first_loc[0]"),
                                  json_number(a[1], where + ": first_loc[1]"),
                                  json_number(a[2], where + ": first_loc[2]")};
  }
  return n;
}

}  // namespace

Dtg parse_dtg(const std::string& text, const std::string& source) {
  const nlohmann::json doc = base::parse_json_document(text, source);
  Dtg g;
  if (const auto* app = json_find(doc, "app")) g.app = json_string(*app, source + ": app");
  const auto& nodes = json_array(json_member(doc, "nodes", source), source + ": nodes");
  // Task nodes first, then sync nodes, each in the order of their numbers (the runtime's order).
  std::map<std::pair<int, int>, DtgNode> by_id;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const std::string where = source + ": nodes[" + std::to_string(i) + "]";
    DtgNode n = parse_node(nodes[i], where);
    const auto key = std::make_pair(n.type == DtgNodeType::task ? 0 : 1, n.number);
    if (!by_id.emplace(key, std::move(n)).second)
      throw InputError(where + ": a second node with the same id");
  }
  std::map<std::pair<int, int>, int> index;
  for (auto& [key, n] : by_id) {
    index[key] = static_cast<int>(g.nodes.size());
    g.nodes.push_back(std::move(n));
  }
  for (DtgNode& n : g.nodes) {
    if (n.type != DtgNodeType::sync || n.waiter < 0) continue;
    const auto it = index.find({0, n.waiter});
    if (it == index.end())
      throw InputError(source + ": sync node s" + std::to_string(n.number) + ": waiter t" +
                       std::to_string(n.waiter) + " is no task node");
    n.waiter = it->second;
    n.kind = g.nodes[static_cast<std::size_t>(it->second)].kind;
  }
  // Scripts name tasks by id: read once every node has its index.
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const auto* script = json_find(nodes[i], "script");
    if (!script) continue;
    const std::string where = source + ": nodes[" + std::to_string(i) + "]: script";
    const auto [type, number] =
        parse_id(json_string(json_member(nodes[i], "id", where), where), where);
    if (type != DtgNodeType::task) throw InputError(where + ": only task nodes have a script");
    DtgNode& n = g.nodes[static_cast<std::size_t>(index.at({0, number}))];
    const auto& steps = json_array(*script, where);
    for (std::size_t k = 0; k < steps.size(); ++k) {
      DtgStep st = parse_step(steps[k], where + "[" + std::to_string(k) + "]", index);
      const bool acts = st.op == DtgStep::Op::act;
      n.script.push_back(std::move(st));
      // An await names actions queued before it; a spawn follows the spawned task's creation.
      if (acts) continue;
      for (int a : n.script.back().actions)
        if (a < 0 || a >= static_cast<int>(
                              std::count_if(n.script.begin(), n.script.end(), [](const DtgStep& x) {
                                return x.op == DtgStep::Op::act && !x.raised;  // refused: no aN
                              })))
          throw InputError(where + "[" + std::to_string(k) + "]: awaits action a" +
                           std::to_string(a) + ", not queued before it");
    }
    n.has_script = true;
  }
  const auto& edges = json_array(json_member(doc, "edges", source), source + ": edges");
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const std::string where = source + ": edges[" + std::to_string(i) + "]";
    auto end = [&](const char* key) {
      const auto [type, number] =
          parse_id(json_string(json_member(edges[i], key, where), where + ": " + key), where);
      const auto it = index.find({type == DtgNodeType::task ? 0 : 1, number});
      if (it == index.end()) throw InputError(where + ": " + key + " names no node");
      return it->second;
    };
    DtgEdge e{
        end("from"), end("to"),
        edge_type_of(json_string(json_member(edges[i], "type", where), where + ": type"), where)};
    if (g.nodes[static_cast<std::size_t>(e.to)].type !=
        (e.type == DtgEdgeType::sync ? DtgNodeType::sync : DtgNodeType::task))
      throw InputError(where + ": a " + json_string(json_member(edges[i], "type", where), where) +
                       " edge ends at the wrong type of node");
    g.edges.push_back(e);
  }
  return g;
}

}  // namespace swath::fleet
