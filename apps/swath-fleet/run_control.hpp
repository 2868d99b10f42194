#pragma once
// The orders a `swath-fleet run` takes from outside while it flies (docs/swath-fleet.md, "Abort
// and control"): SIGINT and SIGTERM (an abort: every airborne vehicle told to return, or land),
// and the verbs of `swath-fleet ctl` over a local Unix socket (--ctl-socket PATH). The signal
// handler only notes the signal (async-signal-safe); the runtime polls poll() between its steps.
// A second signal during the abort changes nothing: the orders to the vehicles are sent all the
// same (SIGKILL is the way to stop at once).

#include <deque>
#include <optional>
#include <string>

#include "swath/fleet/control.hpp"

namespace swath::apps {

/// The control socket's verbs and their orders; nullopt for any other word.
std::optional<fleet::ControlOrder> ctl_order(const std::string& verb);

/// The first SIGINT or SIGTERM a run's RunControl noted; 0: none (or no run under way). For the
/// threads that wait on an app (python_app.cpp): a signal must stop an app that keeps its turn.
int noted_signal();

class RunControl {
 public:
  /// Installs the SIGINT/SIGTERM handlers and, when `socket_path` is not empty, listens there:
  /// the socket made with mode 0600 in a directory the user owns (not writable by others); an
  /// existing path that is not a socket, or a socket another run listens on, is refused
  /// (base::InputError); a stale socket left by a killed run is replaced.
  RunControl(fleet::AbortAction on_abort, std::string socket_path);
  /// Restores the handlers; removes the socket.
  ~RunControl();
  RunControl(const RunControl&) = delete;
  RunControl& operator=(const RunControl&) = delete;

  /// The runtime's ControlSource: a signal first (the abort), else the next verb received.
  fleet::ControlRequest poll();
  /// The first SIGINT or SIGTERM received since construction; 0: none.
  int signal_number() const;
  /// From now on SIGINT and SIGTERM wait (blocked) until the destructor: after an abort nothing
  /// may end the process before its record is written.
  void hold_signals();

 private:
  void accept_clients();
  fleet::AbortAction on_abort_;
  std::string socket_path_;
  int listen_fd_ = -1;
  bool signal_taken_ = false;
  bool signals_held_ = false;
  std::deque<fleet::ControlRequest> orders_;
};

}  // namespace swath::apps
