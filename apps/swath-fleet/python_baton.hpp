// The baton of swath-fleet's Python apps (python_app.cpp): exactly one of the runtime and the
// Python tasks' threads runs at a time.
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>

namespace swath::apps {

/// Who may run: the runtime (kRuntime) or one Python task (its slot). Each side waits on a
/// condition of its own, so a hand-over wakes one thread, not every task's (thousands live).
class Baton {
 public:
  static constexpr int kRuntime = -1;
  /// Runtime side: lets task `slot` run and waits until it hands the baton back, calling
  /// `on_stall` every 100 ms of wall time meanwhile (a task that keeps its turn).
  /// `on_stall` returning true takes the baton back from a task that will not give it: the task
  /// is abandoned (its thread never gets a turn again, and what it sets is no longer read).
  template <class OnStall>
  void run(int slot, std::condition_variable& task_cv, OnStall on_stall) {
    std::unique_lock lock(m_);
    turn_ = slot;
    task_cv.notify_one();
    while (!runtime_cv_.wait_for(lock, std::chrono::milliseconds(100),
                                 [&] { return turn_ == kRuntime; })) {
      lock.unlock();
      const bool give_up = on_stall();
      lock.lock();
      if (give_up) turn_ = kRuntime;
    }
  }
  /// Python side: `commit` (what the task asks of the runtime) and the hand-back happen only
  /// while the turn is still the task's; then it waits for its next turn.
  template <class Commit>
  void yield(int slot, std::condition_variable& task_cv, Commit commit) {
    std::unique_lock lock(m_);
    if (turn_ == slot) {
      commit();
      turn_ = kRuntime;
      runtime_cv_.notify_one();
    }
    task_cv.wait(lock, [&] { return turn_ == slot; });
  }
  void wait_turn(int slot, std::condition_variable& task_cv) {
    std::unique_lock lock(m_);
    task_cv.wait(lock, [&] { return turn_ == slot; });
  }
  /// Python side, when the task's function has returned (`commit` as for yield).
  template <class Commit>
  void finish(int slot, Commit commit) {
    std::lock_guard lock(m_);
    if (turn_ != slot) return;  // abandoned: the runtime has gone on without it
    commit();
    turn_ = kRuntime;
    runtime_cv_.notify_one();
  }

 private:
  std::mutex m_;
  std::condition_variable runtime_cv_;
  int turn_ = kRuntime;
};

}  // namespace swath::apps
