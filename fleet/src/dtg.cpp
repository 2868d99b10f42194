#include "swath/fleet/dtg.hpp"

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
    DtgNode n = nodes[i];
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
