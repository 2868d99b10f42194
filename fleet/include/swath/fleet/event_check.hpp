#pragma once
// An independent judge of a run (docs/swath-fleet.md): reads only events.jsonl — nothing of
// the runtime — and checks the promises of docs/swath-fleet.md, 'Faults' and 'Checked'. Rules:
//   R1 the first line is run_start, the last run_end; times finite, ≥ 0, never going back
//   R2 each task is created once, before anything names it; its parent was created before
//   R3 each created task has exactly one terminal event (task_done, task_cancelled, task_failed)
//   R4 after its terminal event nothing names a task but duplicate_result
//   R5 a result (task, action) is delivered (action_done) at most once; a task's delivered
//      actions in increasing order
//   R6 every state of charge in [0, 1]
//   R7 the run ends by run_start's max_time_s
//   R8 drones named are run_start's; after a motor_failure nothing is dispatched to it (results
//      it sent before are still delivered)
//   R9 a dispatch names a task and segment made visible before, and the task's latest segment;
//      a task's segments are announced (request_visible) in order 0, 1, 2, ...
//   R10 a same_drone task's results (action_done) and dispatches after its first result all name
//      one drone (task_created logs the binding flags)
//   R11 at every drone_state time, two airborne drones (alt_m > 0, not lost) are at least
//      run_start's envelope.separation_m apart (3-D)
//   R12 no drone position (drone_state, drone_mode) nor dispatch target is above
//      envelope.ceiling_m or envelope.fence_max_altitude_m
//   R13 no drone position nor dispatch target is outside every envelope.inclusions ring (when
//      there are any) or inside an envelope.exclusions ring
// The envelope's defaults (ceiling 120 m, separation 5 m, no fence) hold when run_start has none.
// Unknown event kinds are ignored, so the runtime may add events.

#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace swath::fleet {

struct EventViolation {
  int line = 0;      ///< 1-based line of events.jsonl
  std::string rule;  ///< "R1" … "R13"
  std::string message;
};

struct EventCheck {
  std::vector<EventViolation> violations;
  int lines = 0, tasks = 0, results = 0, duplicates = 0, faults = 0;
  /// The least 3-D distance between two airborne drones at a drone_state time, m (infinity: never
  /// two airborne), and the highest drone position, m.
  double least_separation_m = std::numeric_limits<double>::infinity(), max_altitude_m = 0;
  std::map<std::string, int> terminal;  ///< task_done, task_cancelled, task_failed → count
  bool ok() const { return violations.empty(); }
};

/// Checks `text` (the whole events.jsonl). Never throws for any input: malformed lines are
/// violations of R1 naming their line.
EventCheck check_events(const std::string& text);

}  // namespace swath::fleet
