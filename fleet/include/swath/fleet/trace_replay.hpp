#pragma once
// Trace replay (the paper's level-1 simulator, paper 000 §3.3.2; docs/swath-fleet.md): a recorded
// run's task graph played back as an application. Each task of dtg.json carries its program as the
// runtime saw it ("script": actions queued, awaits that suspended, spawns, cancels, compute delays,
// in order), so the replay's tasks appear when their recorded predecessors are done *in this run*
// plus the recorded delay, act where and how the recorded ones did (same places, actions,
// same_drone / interruptible), and recorded cancels fire when their issuer reaches them. Steps the
// app saw throw ("raised": a call refused at the fence or out of reach, an await of a task that
// failed) throw again here; a failed task whose script ends at one ends with that error.
//
// Valid where the graph does not depend on the schedule (cases 1, 3, 4, 5 of docs/swath-fleet.md,
// 'Case studies'): with another scheduler or fleet the places stay the recorded ones, which the
// real app would have changed only if its readings depended on when they were taken. Case 2 (wifi)
// cancels cells by what the readings so far say, so its cancels are the recorded run's, not the
// ones another schedule would make (world replay is the valid method there). An await of a task
// already done leaves no step; before each step the replay awaits the tasks this one spawned that
// had ended before it in the recording (dtg.json "seq", "ended_seq"). Not reproduced: such an await
// of a task another task spawned; an application's random numbers and metrics.

#include <string>

#include "swath/fleet/dtg.hpp"
#include "swath/fleet/runtime.hpp"

namespace swath::fleet {

/// The application that replays `dtg` (its name: the recorded app's). Throws base::InputError
/// when the graph has no scripts (dtg.json written before swath-fleet recorded them) or its main
/// task (t0) is missing.
App make_trace_app(const Dtg& dtg);

/// Why a recorded app's graph depends on the schedule ("" when it does not, as far as swath
/// knows: case 2 wifi is the built-in one that does).
std::string schedule_dependence(const std::string& app);

}  // namespace swath::fleet
