#pragma once
// Orders from outside a run (docs/swath-fleet.md, "Abort and control"): a signal, `swath-fleet ctl`
// over the run's control socket, or the runtime itself when an exception escapes its loop. The
// runtime polls RuntimeSettings::control between its steps (never from a signal handler) and
// carries the order out at the run's current time.

#include <functional>
#include <string>

namespace swath::fleet {

enum class ControlOrder {
  none,      ///< nothing new
  pause,     ///< vehicles hold where they are; the scheduler dispatches nothing
  resume,    ///< after a pause: scheduling goes on
  rtl_all,   ///< abort: every airborne vehicle returns to launch, the run ends
  land_all,  ///< abort: every airborne vehicle lands where it is, the run ends
};

struct ControlRequest {
  ControlOrder order = ControlOrder::none;
  std::string reason;  ///< for the log: "SIGINT", "ctl rtl-all", ...
};

/// What an abort tells the vehicles (`swath-fleet run --on-abort rtl|land`).
enum class AbortAction { rtl, land };

/// Polled by the runtime between steps; returns ControlOrder::none when nothing was asked.
using ControlSource = std::function<ControlRequest()>;

}  // namespace swath::fleet
