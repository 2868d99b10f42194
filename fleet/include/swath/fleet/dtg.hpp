#pragma once
// The dynamic task graph (paper 000 §3.2.1; DESIGN.md §18.3) as a value: what `dtg.json` holds,
// read back for the forecaster (§18.4), the held-out evaluation and replay. Task nodes are the
// application's tasks; a sync node is one await of a coroutine on one or more tasks (consecutive
// awaits with nothing between form one node). Edges: spawn (issuer's latest sync node or task
// node → new task), sync (awaited task → sync node), cancel (issuer → cancelled task).

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "swath/vehicle/vec3.hpp"

namespace swath::fleet {

enum class DtgNodeType { task, sync };
enum class DtgEdgeType { spawn, sync, cancel };
/// running: not ended at the time the graph stands for (a frontier node).
enum class DtgStatus { running, done, cancelled, failed };

struct DtgNode {
  DtgNodeType type = DtgNodeType::task;
  int number = 0;        ///< the n of "tN" / "sN" in dtg.json
  std::string kind;      ///< a task's kind; a sync node: its waiter's kind
  double created_s = 0;  ///< s since the run began
  /// When the task ended, s; infinity while running (sync nodes: infinity).
  double ended_s = std::numeric_limits<double>::infinity();
  DtgStatus status = DtgStatus::running;     ///< sync nodes: running
  std::optional<vehicle::Vec3> first_loc_m;  ///< a task's first fly_to, local metres
  int waiter = -1;  ///< sync nodes: the index of the waiting task's node (-1 when unknown)
};

struct DtgEdge {
  int from = 0, to = 0;  ///< node indices
  DtgEdgeType type = DtgEdgeType::spawn;
};

struct Dtg {
  std::string app;
  std::vector<DtgNode> nodes;  ///< task nodes, then sync nodes, each in creation order
  std::vector<DtgEdge> edges;
  /// The graph as it stood at `t_s`: nodes created by then, tasks not ended by then running,
  /// edges whose ends both exist (a cancel edge once its task ended).
  Dtg as_of(double t_s) const;
};

/// Reads dtg.json. Throws base::InputError "<source>: <place>: <problem>" for anything that is
/// not a DTG: unknown node or edge types, an edge naming an absent node, non-finite times.
Dtg parse_dtg(const std::string& text, const std::string& source);

}  // namespace swath::fleet
