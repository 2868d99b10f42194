#include "dtg_index.hpp"

#include <algorithm>
#include <limits>

namespace swath::fleet::detail {

namespace {

bool ended(const DtgNode& n) {
  return n.status != DtgStatus::running;
}

}  // namespace

DtgIndex::DtgIndex(const Dtg& g)
    : parents(g.nodes.size()),
      spawned(g.nodes.size()),
      awaited_by(g.nodes.size()),
      cancelled(g.nodes.size()),
      next_known(g.nodes.size(), 0),
      next(g.nodes.size()) {
  for (const DtgEdge& e : g.edges) switch (e.type) {
      case DtgEdgeType::spawn:
        parents[at(e.to)].push_back(e.from);
        spawned[at(e.from)].push_back(e.to);
        break;
      case DtgEdgeType::sync:
        parents[at(e.to)].push_back(e.from);
        awaited_by[at(e.from)].push_back(e.to);
        break;
      case DtgEdgeType::cancel:
        cancelled[at(e.from)].push_back(e.to);
        break;
    }
  // Each waiter's sync nodes in creation order: an iteration runs from one to the next.
  std::vector<std::vector<int>> syncs_of(g.nodes.size());
  for (std::size_t s = 0; s < g.nodes.size(); ++s)
    if (g.nodes[s].type == DtgNodeType::sync && g.nodes[s].waiter >= 0)
      syncs_of[at(g.nodes[s].waiter)].push_back(static_cast<int>(s));
  for (std::size_t c = 0; c < g.nodes.size(); ++c) {
    if (g.nodes[c].type != DtgNodeType::task || awaited_by[c].empty()) continue;
    const int s = *std::min_element(awaited_by[c].begin(), awaited_by[c].end());
    const DtgNode& sync = g.nodes[at(s)];
    bool resolved = true;
    for (int a : parents[at(s)]) resolved &= ended(g.nodes[at(a)]);
    if (!resolved) continue;
    next_known[c] = 1;
    std::vector<int> out = spawned[at(s)];
    if (out.empty() && sync.waiter >= 0) {
      // The waiter acted between (its spawns then leave its task node): what it spawned from its
      // task node after this sync and before its next one.
      double until = std::numeric_limits<double>::infinity();
      for (int o : syncs_of[at(sync.waiter)])
        if (o != s && g.nodes[at(o)].created_s > sync.created_s)
          until = std::min(until, g.nodes[at(o)].created_s);
      for (int k : spawned[at(sync.waiter)])
        if (g.nodes[at(k)].created_s >= sync.created_s && g.nodes[at(k)].created_s < until)
          out.push_back(k);
    }
    for (int k : out)
      if (g.nodes[at(k)].first_loc_m) next[c].push_back(k);
  }
}

}  // namespace swath::fleet::detail
