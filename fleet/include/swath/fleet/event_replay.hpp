#pragma once
// A run's record read back from its events.jsonl (swath-fleet render): the drones' names, tracks
// and spans of what they did, where they sensed and where requests were cancelled, the end — what
// the pictures need, as the runtime recorded them (it logs every track point: drone_state at the
// state period and drone_mode at each change, with the change's own time at_s).

#include <string>

#include "swath/fleet/runtime.hpp"

namespace swath::fleet {

/// Throws base::InputError "<source>: line N: <problem>" for a line that is not an event or an
/// event without the fields it needs; ignores the kinds it does not use.
RunRecord replay_record(const std::string& events_jsonl, const std::string& source);

}  // namespace swath::fleet
