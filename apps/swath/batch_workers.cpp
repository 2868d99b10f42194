#include "batch_workers.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>

#include "command.hpp"
#include "plan_command.hpp"
#include "progress_bar.hpp"
#include "swath/base/freed_memory.hpp"
#include "swath/base/number_text.hpp"

namespace swath::apps {
namespace {

// A process per area cost each plan a fork, an exit and a fresh heap: about 2,800 page faults an
// area in a batch against 1,500-2,300 for a plan run alone, and a tenth of the batch's CPU in the
// kernel. A worker keeps its heap and caches from one area to the next. It is retired after
// kAreasPerWorker areas, so that whatever a plan may leave behind (memory, descriptors) stays
// bounded, and after a death, which fails only the area it was planning.
constexpr std::size_t kAreasPerWorker = 64;

// Resident memory a worker keeps after an area (the freed memory above it goes back to the
// system): a plan keeps what it frees for its next buffers (base::keep_freed_memory()), and a
// worker would keep its largest area's memory, 300 MB after a 334 MB area, through the areas
// after it; N workers N times that. A traced outline's plan peaks at 15-39 MB on one thread.
constexpr std::size_t kKeptAfterArea_bytes = std::size_t{256} << 20;

// Areas a worker plans before it is replaced: kAreasPerWorker, or 1 under a limit that a process
// counts over its whole life (ulimit -t, -v, -d). `swath plan` alone has the whole of such a limit
// for its area; a worker's second area only what the first left of it (CPU seconds, address space
// kept for the next plan), and an area that plans alone was killed or ran out of memory.
std::size_t areas_per_worker() {
  for (const int resource : {RLIMIT_CPU, RLIMIT_AS, RLIMIT_DATA}) {
    struct rlimit limit {};
    if (::getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) return 1;
  }
  return kAreasPerWorker;
}

// The workers' processes, for a signal that ends the batch. A worker is told of its batch's end by
// PR_SET_PDEATHSIG (SIGTERM), but a stopped worker (SIGSTOP, a debugger, Ctrl-Z of the worker
// alone) takes no signal until it is continued, and nothing continues it once the batch is gone:
// it stayed stopped for good, an orphan holding its area's temporaries. So a SIGINT, SIGTERM or
// SIGHUP that ends the batch first sends each worker SIGTERM and SIGCONT (async-signal-safe:
// fixed storage, kill(), raise()). A worker, forked with these handlers, finds another pid in
// g_batch_pid and only ends as the signal would.
constexpr std::size_t kMaxWorkers = 256;  // --jobs' upper limit
volatile sig_atomic_t g_worker_pids[kMaxWorkers] = {};
volatile sig_atomic_t g_batch_pid = 0;
constexpr int kEndingSignals[] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void end_workers_and_die(int signal_number) {
  if (::getpid() == g_batch_pid)
    for (const volatile sig_atomic_t& pid : g_worker_pids)
      if (pid > 0) {
        ::kill(pid, SIGTERM);
        ::kill(pid, SIGCONT);
      }
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

// The handlers above for the life of a pool, where the batch does not ignore the signal (nohup,
// a background job of a script: then its workers ignore it too).
class WorkerSignals {
 public:
  WorkerSignals() {
    g_batch_pid = ::getpid();
    for (std::size_t i = 0; i < std::size(kEndingSignals); ++i) {
      struct sigaction action {};
      action.sa_handler = end_workers_and_die;
      sigemptyset(&action.sa_mask);
      for (const int s : kEndingSignals) sigaddset(&action.sa_mask, s);
      ::sigaction(kEndingSignals[i], nullptr, &previous_[i]);
      if (previous_[i].sa_handler != SIG_IGN) ::sigaction(kEndingSignals[i], &action, nullptr);
    }
  }
  ~WorkerSignals() {
    for (std::size_t i = 0; i < std::size(kEndingSignals); ++i)
      ::sigaction(kEndingSignals[i], &previous_[i], nullptr);
    for (volatile sig_atomic_t& pid : g_worker_pids) pid = 0;
  }
  WorkerSignals(const WorkerSignals&) = delete;
  WorkerSignals& operator=(const WorkerSignals&) = delete;

 private:
  struct sigaction previous_[std::size(kEndingSignals)]{};
};

struct Worker {
  pid_t pid = -1;
  int socket = -1;                 ///< ours of a socket pair: area indices out, exit codes in
  int log = -1;                    ///< its stderr: an anonymous file in memory (memfd)
  std::optional<std::size_t> job;  ///< the area it is planning
  std::chrono::steady_clock::time_point deadline;  ///< when that area's time is up
  std::size_t planned = 0;
};

using Clock = std::chrono::steady_clock;

bool send_all(int fd, const void* data, std::size_t size) {
  const char* at = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::send(fd, at, size, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    at += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

// False at the end of the stream (the other side closed or died) or on an error.
bool receive_all(int fd, void* data, std::size_t size) {
  char* at = static_cast<char*>(data);
  while (size > 0) {
    const ssize_t n = ::recv(fd, at, size, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    at += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

// `swath plan` with `argv`, in this process, as its own process would run it.
int plan_here(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::vector<std::unique_ptr<Command>> plan;
  plan.push_back(std::make_unique<PlanCommand>());
  const int code =
      run_program("swath", "swath plan", "", plan, static_cast<int>(argv.size()), args.data());
  std::cout.flush();
  std::cerr.flush();
  return code;
}

// A worker's life: plans each area it is sent and answers with the exit code, until the batch
// closes its side; never returns.
[[noreturn]] void work(const std::vector<std::vector<std::string>>& commands, int socket, int log,
                       pid_t parent) {
  // A batch ended by a signal ends its workers too (each plan removes its temporaries as it goes).
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);
  if (::getppid() != parent) ::_exit(128 + SIGTERM);  // the parent went before prctl took hold
  const int out = ::open("/dev/null", O_WRONLY);
  ::dup2(out, 1);
  ::dup2(log, 2);
  for (std::uint32_t job = 0; receive_all(socket, &job, sizeof job);) {
    const std::int32_t code = job < commands.size() ? plan_here(commands[job]) : 2;
    base::give_back_freed_memory(kKeptAfterArea_bytes);
    if (!send_all(socket, &code, sizeof code)) break;
  }
  ::_exit(0);
}

// The first MiB of a worker's log.
std::string read_log(int fd) {
  // As long as the log is (a plan writes a line or none): a MiB zeroed for every area was a
  // fifth of the batch's own CPU.
  struct stat st {};
  const std::size_t size = ::fstat(fd, &st) == 0 && st.st_size >= 0
                               ? static_cast<std::size_t>(st.st_size)
                               : std::size_t{1} << 20;
  std::string text(std::min(size, std::size_t{1} << 20), '\0');
  const ssize_t n = ::pread(fd, text.data(), text.size(), 0);
  text.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  return text;
}

class Pool {
 public:
  Pool(const std::vector<std::vector<std::string>>& commands, int parallel, double timeout_s)
      : commands_(commands),
        workers_(static_cast<std::size_t>(parallel)),
        areas_per_worker_(areas_per_worker()),
        timeout_s_(timeout_s) {}
  ~Pool() {
    for (Worker& w : workers_) {
      if (w.job && w.pid > 0) {  // the batch is failing: not its end
        ::kill(w.pid, SIGTERM);
        ::kill(w.pid, SIGCONT);
      }
      retire(w);
    }
  }
  Pool(const Pool&) = delete;
  Pool& operator=(const Pool&) = delete;

  // `w` (idle or without a process) given area `job`, a fresh process first where it has none or
  // has planned its share. A process that has planned areas and ended since (a signal, the OOM
  // killer: between two areas) was planning none: a fresh one takes `job`. False: a fresh process
  // died before it could take it (`job` is then failed with its exit status, in `r`).
  bool give(Worker& w, std::size_t job, PlanResult& r) {
    if (w.pid > 0 && w.planned >= areas_per_worker_) retire(w);
    const std::uint32_t index = static_cast<std::uint32_t>(job);
    for (;;) {
      if (w.pid <= 0) start(w);
      w.job = job;
      // The log emptied here, not by the worker: a worker killed before it could would leave the
      // last area's words in this one's row. Idle, it writes nothing; the file offset is shared
      // with its stderr (the same open file), and the batch reads with pread().
      if (::ftruncate(w.log, 0) != 0 || ::lseek(w.log, 0, SEEK_SET) != 0)
        throw std::runtime_error("batch: cannot empty a planning process's log");
      if (send_all(w.socket, &index, sizeof index)) {
        if (timeout_s_ > 0)
          w.deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                          std::chrono::duration<double>(timeout_s_));
        return true;
      }
      if (w.planned == 0) break;
      w.job.reset();
      retire(w);  // reaped; its status is no area's
    }
    r = ended(w);
    return false;
  }

  // Waits until some busy worker answers, dies or runs out of time: the area it planned, and its
  // result.
  std::pair<std::size_t, PlanResult> next_result() {
    std::vector<pollfd> polled;
    std::vector<Worker*> busy;
    for (Worker& w : workers_)
      if (w.job) {
        polled.push_back({w.socket, POLLIN, 0});
        busy.push_back(&w);
      }
    if (busy.empty()) throw std::logic_error("batch: no area is being planned");
    // The answers first, then the deadlines: an answer that came while the batch was not
    // waiting (ending another worker, stopped) is the area's, however late.
    for (;;) {
      const int wait = wait_ms(busy);
      const Clock::time_point asked = Clock::now();
      const int ready = ::poll(polled.data(), polled.size(), wait);
      if (ready > 0) break;
      if (ready < 0 && errno != EINTR)
        throw std::runtime_error("batch: cannot wait for the planning processes");
      discount_stop(busy, asked, wait);
      if (Worker* late = out_of_time(busy)) {
        const std::size_t job = *late->job;
        return {job, timed_out(*late)};
      }
    }
    for (std::size_t i = 0; i < busy.size(); ++i) {
      if (polled[i].revents == 0) continue;
      Worker& w = *busy[i];
      const std::size_t job = *w.job;
      std::int32_t code = 0;
      if (!receive_all(w.socket, &code, sizeof code)) return {job, ended(w)};
      w.job.reset();
      ++w.planned;
      return {job, PlanResult{code, first_line(read_log(w.log))}};
    }
    throw std::logic_error("batch: poll answered for no planning process");
  }

  std::vector<Worker>& workers() { return workers_; }

 private:
  static std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

  // The first busy worker whose area's time is up (none without a timeout).
  Worker* out_of_time(const std::vector<Worker*>& busy) const {
    if (!(timeout_s_ > 0)) return nullptr;
    const Clock::time_point now = Clock::now();
    for (Worker* w : busy)
      if (w->deadline <= now) return w;
    return nullptr;
  }

  // Milliseconds until the earliest deadline of the busy workers (rounded up); -1: no timeout.
  int wait_ms(const std::vector<Worker*>& busy) const {
    if (!(timeout_s_ > 0)) return -1;
    Clock::time_point first = Clock::time_point::max();
    for (const Worker* w : busy) first = std::min(first, w->deadline);
    const double ms = std::chrono::duration<double, std::milli>(first - Clock::now()).count();
    return static_cast<int>(std::clamp(std::ceil(ms), 0.0, 60'000.0));
  }

  // A wait for the deadlines that ended more than a second later than asked: the batch was
  // stopped (Ctrl-Z stops the whole job, its workers too) or the machine paused. The whole wait is
  // then not counted against the areas being planned (when the stop began within it is unknown:
  // an area may get up to the wait's length more).
  static void discount_stop(const std::vector<Worker*>& busy, Clock::time_point asked, int wait) {
    if (wait < 0) return;
    const Clock::duration waited = Clock::now() - asked;
    if (waited > std::chrono::milliseconds(wait) + std::chrono::seconds(1))
      for (Worker* w : busy) w->deadline += waited;
  }

  // `w`'s area failed for taking longer than the timeout, and its process ended (end_process()).
  // Unless the area's answer came before its process ended: then that is the area's result (its
  // plan finished, its files switched in; a SIGTERM while a plan renames its files into place
  // waits until they are all in).
  PlanResult timed_out(Worker& w) {
    end_process(w.pid, std::chrono::seconds(0));
    w.pid = -1;  // ended
    note_pid(w);
    std::int32_t code = 0;
    const bool answered = ::recv(w.socket, &code, sizeof code, MSG_DONTWAIT) == sizeof code;
    PlanResult r{base::kExitFailure, ""};
    if (answered) {
      r = PlanResult{code, first_line(read_log(w.log))};
    } else {
      r.timed_out = true;
      r.message = "swath batch: planning took longer than --timeout-s " +
                  base::shortest_text(timeout_s_) + " s; its process was ended";
    }
    w.job.reset();
    retire(w);
    return r;
  }

  // Ends process `pid`: it is given `grace` to end on its own (a worker whose socket was closed
  // exits), then SIGTERM (which removes a plan's temporaries) with SIGCONT (a stopped process
  // takes its SIGTERM only once continued), 2 s later SIGKILL; reaped as soon as it ends. A
  // process that SIGKILL does not end within 2 s more (stuck in the kernel: a hung network mount)
  // is left to end on its own; init reaps it once the batch has exited.
  static void end_process(pid_t pid, Clock::duration grace) {
    // Looked at after 0.1, 0.2, 0.4 ... ms, then every 2 ms: a worker told to end by its socket
    // exits within about a millisecond (hand-overs, each area's under `ulimit -t`).
    const auto reaped_by = [pid](Clock::time_point until) {
      for (useconds_t pause_us = 100;; pause_us = std::min<useconds_t>(2 * pause_us, 2'000)) {
        const pid_t r = ::waitpid(pid, nullptr, WNOHANG);
        if (r == pid || (r < 0 && errno != EINTR)) return true;
        if (Clock::now() >= until) return false;
        ::usleep(pause_us);
      }
    };
    if (reaped_by(Clock::now() + grace)) return;
    ::kill(pid, SIGTERM);
    ::kill(pid, SIGCONT);
    if (reaped_by(Clock::now() + std::chrono::seconds(2))) return;
    ::kill(pid, SIGKILL);
    reaped_by(Clock::now() + std::chrono::seconds(2));
  }

  void start(Worker& w) {
    int pair[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, pair) != 0)
      throw std::runtime_error("batch: cannot connect to a planning process");
    w.socket = pair[0];
    w.log = ::memfd_create("swath-batch-log", MFD_CLOEXEC);
    if (w.log < 0) throw std::runtime_error("batch: cannot create a log for a planning process");
    std::cout.flush();
    std::cerr.flush();
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error("batch: cannot start a process");
    if (pid == 0) {
      // Only its own descriptors: a worker keeping another's socket open would keep that one
      // from seeing the batch close it.
      for (const Worker& other : workers_)
        if (&other != &w && other.socket >= 0) {
          ::close(other.socket);
          ::close(other.log);
        }
      ::close(pair[0]);
      work(commands_, pair[1], w.log, parent);
    }
    ::close(pair[1]);
    w.pid = pid;
    note_pid(w);
    w.planned = 0;
  }

  // The result of the area `w` was planning when its process died, and `w` without a process.
  PlanResult ended(Worker& w) {
    int status = 0;
    while (::waitpid(w.pid, &status, 0) < 0 && errno == EINTR) {
    }
    PlanResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    if (r.exit_code == 0) r.exit_code = base::kExitFailure;  // it ended without an answer
    r.message = first_line(read_log(w.log));
    if (r.message.empty() && WIFSIGNALED(status))
      r.message = "swath plan: its process ended by signal " + std::to_string(WTERMSIG(status)) +
                  " (" + ::strsignal(WTERMSIG(status)) + ")";
    w.pid = -1;  // already reaped
    note_pid(w);
    w.job.reset();
    retire(w);
    return r;
  }

  // `w`'s process told to end (its socket closed) and reaped (ended, after 5 s: one stopped
  // between two areas never reads its socket's end); its descriptors closed.
  void retire(Worker& w) {
    if (w.socket >= 0) ::close(w.socket);
    if (w.pid > 0) end_process(w.pid, std::chrono::seconds(5));
    if (w.log >= 0) ::close(w.log);
    w = Worker{};
    note_pid(w);
  }

  // `w`'s process as the signal handler sees it (none once reaped).
  void note_pid(const Worker& w) {
    const auto slot = static_cast<std::size_t>(&w - workers_.data());
    if (slot < kMaxWorkers) g_worker_pids[slot] = w.pid > 0 ? w.pid : 0;
  }

  WorkerSignals signals_;  // before the workers: restored after they are ended
  const std::vector<std::vector<std::string>>& commands_;
  std::vector<Worker> workers_;
  std::size_t areas_per_worker_;
  double timeout_s_;  ///< wall-clock seconds an area may take; 0: no limit
};

}  // namespace

const char* batch_status(const PlanResult& r) {
  if (r.timed_out) return "timed-out";
  if (r.exit_code == base::kExitSuccess) return "planned";
  return r.exit_code == base::kExitBadInput ? "refused" : "failed";
}

std::vector<PlanResult> plan_in_workers(const std::vector<std::vector<std::string>>& commands,
                                        int parallel, bool progress, double timeout_s) {
  std::vector<PlanResult> results(commands.size());
  ProgressBar bar(progress, "planning");
  Pool pool(commands, std::max(1, std::min(parallel, static_cast<int>(commands.size()))),
            timeout_s);
  std::size_t next = 0, done = 0;
  const auto finish = [&](std::size_t job, PlanResult r) {
    results[job] = std::move(r);
    bar.update(static_cast<double>(++done) / static_cast<double>(commands.size()));
  };
  const auto fill = [&] {
    for (Worker& w : pool.workers())
      while (!w.job && next < commands.size()) {
        PlanResult r;
        const std::size_t job = next++;
        if (!pool.give(w, job, r)) finish(job, std::move(r));
      }
  };
  fill();
  while (done < commands.size()) {
    auto [job, r] = pool.next_result();
    finish(job, std::move(r));
    fill();
  }
  return results;
}

}  // namespace swath::apps
