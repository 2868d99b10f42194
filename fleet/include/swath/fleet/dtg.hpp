#pragma once
// The dynamic task graph (paper 000 §3.2.1; docs/swath-fleet.md) as a value: what `dtg.json` holds,
// read back for the forecaster, the held-out evaluation and replay. Task nodes are the
// application's tasks; a sync node is one await of a coroutine on one or more tasks (consecutive
// awaits with nothing between form one node). Edges: spawn (issuer's latest sync node or task
// node → new task), sync (awaited task → sync node), cancel (issuer → cancelled task).

#include <cstdint>
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

/// One step of a task's program as the runtime recorded it (dtg.json "script"), in the order the
/// task made them: what trace replay (trace_replay.hpp) plays back.
struct DtgStep {
  enum class Op { act, await, spawn, cancel, delay };
  Op op = Op::act;
  /// act: 0 fly_to, 1 sense, 2 hover, 3 custom, 4 fly_sensing (Ctx's actions).
  int action = 0;
  vehicle::Vec3 to_m;  ///< fly_to, fly_sensing: the target, local metres
  std::string name;    ///< sense, fly_sensing: the sensor; custom: the action's name
  /// hover, custom: duration, s; fly_sensing: the sampling period, s; delay: the compute cost, s.
  double seconds = 0;
  /// await: the awaited tasks' node indices, in order; spawn, cancel: the one task's node index.
  std::vector<int> tasks;
  std::vector<int> actions;  ///< await: indices of the task's own actions awaited
  bool any = false;          ///< await: one `any` over all of them (else each in turn)
  /// The app saw this step throw — act: the call was refused (outside the fence, out of reach,
  /// ...), no action queued, so it has no "aN"; await: an awaited task had failed or was
  /// cancelled. A task whose script ends at such a step, failed, let the error end it.
  bool raised = false;
  /// Its place in the order of all steps and task ends of the run (-1: not recorded).
  std::int64_t seq = -1;
};

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
  bool same_drone = false, interruptible = true;  ///< a task's binding flags (when recorded)
  /// A task's program (empty in a dtg.json written before scripts were recorded: has_script).
  std::vector<DtgStep> script;
  bool has_script = false;
  /// A task's end in the order of all script steps and task ends (-1: not ended or unrecorded).
  std::int64_t ended_seq = -1;
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
  /// edges whose ends both exist (a cancel edge once its task ended); no scripts.
  Dtg as_of(double t_s) const;
};

/// Reads dtg.json. Throws base::InputError "<source>: <place>: <problem>" for anything that is
/// not a DTG: unknown node or edge types, an edge naming an absent node, non-finite times.
Dtg parse_dtg(const std::string& text, const std::string& source);

}  // namespace swath::fleet
