// swath-fleet run's abort and control (docs/swath-fleet.md, "Abort and control"), as a user meets
// them: a run on the simulated fleet, paced to the wall clock (--pace), in a child process; SIGINT
// or SIGTERM mid-run, or `swath-fleet ctl` over its socket. The truth each test checks against is
// the run's own log read back: which drones were in the air when the abort came (their last
// drone_mode before the `aborted` event), against the drones the abort commanded; a log that ends
// with run_end and passes `swath-fleet check`; exit 130 / 143 / 4.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "cli_runner.hpp"

extern char** environ;

namespace swath::test::fleet_abort {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// swath-fleet with `args`, stdout and stderr to files beside (not in) the output directory.
pid_t start_fleet(const std::vector<std::string>& args, const std::string& log_base) {
  std::vector<std::string> all{SWATH_FLEET_BINARY};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t io;
  posix_spawn_file_actions_init(&io);
  posix_spawn_file_actions_addopen(&io, 1, (log_base + ".out").c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_addopen(&io, 2, (log_base + ".err").c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_addchdir_np(&io, SWATH_SOURCE_DIR);
  pid_t pid = 0;
  EXPECT_EQ(posix_spawn(&pid, SWATH_FLEET_BINARY, &io, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&io);
  return pid;
}

int wait_exit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Three drones on the sites world's multiplexing app, 20 simulated seconds per wall second.
std::vector<std::string> paced_run(const std::string& out, std::vector<std::string> more = {}) {
  std::vector<std::string> a{"run", "multiplexing", "--world", "sites", "--drones",
                             "3",   "--pace",       "20",      "-o",    out};
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

std::vector<json> events_of(const std::string& out) {
  std::vector<json> events;
  std::istringstream in(read_text(out + "/events.jsonl"));
  for (std::string line; std::getline(in, line);) events.push_back(json::parse(line));
  return events;
}

bool on_the_ground(const std::string& state) {
  return state == "landed" || state == "charging" || state == "lost";
}

// Waits until the run says on stderr that a drone is airborne ("swath-fleet run: drone-1 airborne
// at 2.0 s"), or 120 s: an abort or a pause then finds drones in the air however loaded the
// machine is. False when the line never came.
bool wait_until_airborne(const std::string& err_path) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline) {
    std::ifstream in(err_path);
    const std::string text{std::istreambuf_iterator<char>(in), {}};
    if (text.find(" airborne at ") != std::string::npos) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

// What the log says about the abort: the drones in the air when it came (each drone's last
// drone_mode before it) and the drones it commanded, with the command.
struct AbortSeen {
  int aborted_events = 0;
  std::string reason, action;
  std::set<int> airborne;
  std::map<int, std::string> commanded;
  bool ends_with_run_end = false;
};

AbortSeen read_abort(const std::vector<json>& events) {
  AbortSeen a;
  std::map<int, std::string> state;
  bool after = false;
  for (const json& e : events) {
    const std::string ev = e.at("ev");
    if (ev == "aborted") {
      ++a.aborted_events;
      a.reason = e.at("reason");
      a.action = e.at("action");
      for (const auto& [drone, s] : state)
        if (!on_the_ground(s)) a.airborne.insert(drone);
      after = true;
    } else if (ev == "abort_command") {
      EXPECT_TRUE(after) << "an abort_command before the aborted event";
      a.commanded[e.at("drone").get<int>()] = e.at("command");
    } else if (ev == "drone_mode" && !after) {
      state[e.at("drone").get<int>()] = e.at("state");
    }
  }
  a.ends_with_run_end = !events.empty() && events.back().at("ev") == "run_end";
  return a;
}

// The abort as the log must show it: one aborted event, every drone in the air commanded (and
// only those), the record closed and every rule of `swath-fleet check` holding.
void expect_complete_abort(const std::string& out, const std::string& reason,
                           const std::string& command) {
  const AbortSeen a = read_abort(events_of(out));
  EXPECT_EQ(a.aborted_events, 1);
  EXPECT_EQ(a.reason, reason);
  EXPECT_EQ(a.action, command);
  EXPECT_FALSE(a.airborne.empty()) << "the abort should come while drones fly";
  std::set<int> commanded;
  for (const auto& [drone, c] : a.commanded) {
    commanded.insert(drone);
    EXPECT_EQ(c, command) << "drone " << drone;
  }
  EXPECT_EQ(commanded, a.airborne);
  EXPECT_TRUE(a.ends_with_run_end);
  const CliRun check = run_swath_fleet("check " + out);
  EXPECT_EQ(check.exit_code, 0) << check.out;
  EXPECT_FALSE(json::parse(read_text(out + "/summary.json")).at("completed").get<bool>());
}

TEST(FleetAbortCli, SigintMidRunSendsEveryAirborneDroneHomeAndClosesTheLog) {
  const std::string out = fresh_dir("fleet-sigint");
  const pid_t pid = start_fleet(paced_run(out), out);
  ASSERT_TRUE(wait_until_airborne(out + ".err")) << read_text(out + ".err");
  ASSERT_EQ(kill(pid, SIGINT), 0);
  EXPECT_EQ(wait_exit(pid), 130) << read_text(out + ".err");
  expect_complete_abort(out, "SIGINT", "rtl");
  EXPECT_NE(read_text(out + ".err").find("aborted (SIGINT)"), std::string::npos);
}

// A second (and third) SIGINT while the first one's abort runs changes nothing: the same orders,
// the same complete record.
TEST(FleetAbortCli, RepeatedSigintsStillCommandEveryAirborneDrone) {
  const std::string out = fresh_dir("fleet-sigint-twice");
  const pid_t pid = start_fleet(paced_run(out), out);
  ASSERT_TRUE(wait_until_airborne(out + ".err")) << read_text(out + ".err");
  for (int k = 0; k < 3; ++k) {
    ASSERT_EQ(kill(pid, SIGINT), 0);
    // The second at once (before the loop has even taken the first), the third during the abort.
    if (k == 1) std::this_thread::sleep_for(std::chrono::milliseconds(30));
  }
  EXPECT_EQ(wait_exit(pid), 130) << read_text(out + ".err");
  expect_complete_abort(out, "SIGINT", "rtl");
}

TEST(FleetAbortCli, SigtermWithOnAbortLandLandsEveryAirborneDrone) {
  const std::string out = fresh_dir("fleet-sigterm-land");
  const pid_t pid = start_fleet(paced_run(out, {"--on-abort", "land"}), out);
  ASSERT_TRUE(wait_until_airborne(out + ".err")) << read_text(out + ".err");
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  EXPECT_EQ(wait_exit(pid), 143) << read_text(out + ".err");
  expect_complete_abort(out, "SIGTERM", "land");
}

// A socket directory of the test's own, closed to others.
std::string socket_dir(const std::string& name) {
  const std::string dir = fresh_dir(name);
  fs::create_directories(dir);
  fs::permissions(dir, fs::perms::owner_all, fs::perm_options::replace);
  return dir;
}

bool wait_for_socket(const std::string& path) {
  for (int k = 0; k < 200; ++k) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) == 0 && S_ISSOCK(st.st_mode)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

// pause: the drones on their way stop (requeued, hovering, not moving) and nothing is dispatched
// until resume; resume dispatches again; rtl-all ends the run like an abort (exit 4).
TEST(FleetAbortCli, CtlPauseHoldsAndDispatchesNothingResumeGoesOnRtlAllEnds) {
  const std::string dir = socket_dir("fleet-ctl");
  const std::string sock = dir + "/ctl.sock", out = dir + "/run";
  const pid_t pid = start_fleet(paced_run(out, {"--ctl-socket", sock}), dir + "/log");
  ASSERT_TRUE(wait_for_socket(sock));
  struct stat st {};
  ASSERT_EQ(::stat(sock.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  ASSERT_TRUE(wait_until_airborne(dir + "/log.err")) << read_text(dir + "/log.err");
  const CliRun pause = run_swath_fleet("ctl pause --socket " + sock);
  EXPECT_EQ(pause.exit_code, 0) << pause.err;
  EXPECT_EQ(pause.out, "swath-fleet ctl: ok pause\n");
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // ~30 s paused
  EXPECT_EQ(run_swath_fleet("ctl resume --socket " + sock).exit_code, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  EXPECT_EQ(run_swath_fleet("ctl rtl-all --socket " + sock).exit_code, 0);
  EXPECT_EQ(wait_exit(pid), 4) << read_text(dir + "/log.err");
  EXPECT_FALSE(fs::exists(sock)) << "the run removes its socket";
  expect_complete_abort(out, "ctl rtl-all", "rtl");

  const std::vector<json> events = events_of(out);
  double paused_at = -1, resumed_at = -1;
  std::map<int, std::string> state;
  std::set<int> on_way_at_pause, requeued_for_pause;
  std::map<int, json> held_at;  // where each stopped drone was at the pause
  int dispatched_while_paused = 0, dispatched_after = 0;
  for (const json& e : events) {
    const std::string ev = e.at("ev");
    const double t = e.at("t_s");
    const bool paused = paused_at >= 0 && resumed_at < 0;
    if (ev == "paused") {
      paused_at = t;
      for (const auto& [d, s] : state)
        if (s == "flying" || s == "positioning") on_way_at_pause.insert(d);
    } else if (ev == "resumed") {
      resumed_at = t;
    } else if (ev == "dispatch") {
      (paused ? dispatched_while_paused : dispatched_after) += paused_at >= 0;
    } else if (ev == "requeued" && paused && e.at("reason") == "paused") {
      requeued_for_pause.insert(e.at("drone").get<int>());
    } else if (ev == "drone_mode") {
      const int d = e.at("drone");
      state[d] = e.at("state");
      if (paused && on_way_at_pause.count(d) && !held_at.count(d)) {
        EXPECT_EQ(e.at("state"), "hovering") << "drone " << d << " at the pause";
        held_at[d] = e;
      }
    } else if (ev == "drone_state" && paused && held_at.count(e.at("drone").get<int>()) &&
               e.at("state") == "hovering") {
      const json& h = held_at[e.at("drone").get<int>()];
      EXPECT_NEAR(e.at("x_m").get<double>(), h.at("x_m").get<double>(), 1e-6) << e.dump();
      EXPECT_NEAR(e.at("y_m").get<double>(), h.at("y_m").get<double>(), 1e-6) << e.dump();
    }
  }
  ASSERT_GE(paused_at, 0);
  EXPECT_FALSE(on_way_at_pause.empty()) << "the pause should catch drones on their way";
  ASSERT_GT(resumed_at, paused_at + 10) << "the pause lasted ~30 simulated seconds";
  EXPECT_EQ(dispatched_while_paused, 0);
  EXPECT_GT(dispatched_after, 0) << "resume dispatches again";
  EXPECT_EQ(on_way_at_pause.size(), held_at.size());
  for (int d : requeued_for_pause) EXPECT_TRUE(on_way_at_pause.count(d)) << d;
}

TEST(FleetAbortCli, CtlLandAllLandsEveryAirborneDroneAndEndsTheRun) {
  const std::string dir = socket_dir("fleet-ctl-land");
  const std::string sock = dir + "/ctl.sock", out = dir + "/run";
  const pid_t pid = start_fleet(paced_run(out, {"--ctl-socket", sock}), dir + "/log");
  ASSERT_TRUE(wait_for_socket(sock));
  ASSERT_TRUE(wait_until_airborne(dir + "/log.err")) << read_text(dir + "/log.err");
  EXPECT_EQ(run_swath_fleet("ctl land-all --socket " + sock).exit_code, 0);
  EXPECT_EQ(wait_exit(pid), 4) << read_text(dir + "/log.err");
  expect_complete_abort(out, "ctl land-all", "land");
}

TEST(FleetAbortCli, ACtlSocketPathThatIsNotASocketIsRefusedAndKept) {
  const std::string dir = socket_dir("fleet-ctl-refused");
  const std::string path = dir + "/not-a-socket", out = dir + "/run";
  { std::ofstream(path) << "mine\n"; }
  const CliRun r =
      run_swath_fleet("run multiplexing --world sites --ctl-socket " + path + " -o " + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("not a socket"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(path), "mine\n");
  EXPECT_FALSE(fs::exists(out)) << "nothing written";
  // A directory open to others is refused too.
  const std::string open_dir = fresh_dir("fleet-ctl-open");
  fs::create_directories(open_dir);
  fs::permissions(open_dir, fs::perms::all, fs::perm_options::replace);
  const CliRun o = run_swath_fleet("run multiplexing --world sites --ctl-socket " + open_dir +
                                   "/s.sock -o " + out);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.err.find("not writable by others"), std::string::npos) << o.err;
  // ctl with nobody listening: one sentence, exit 2.
  const CliRun c = run_swath_fleet("ctl pause --socket " + dir + "/nobody.sock");
  EXPECT_EQ(c.exit_code, 2);
  EXPECT_NE(c.err.find("no swath-fleet run listens there"), std::string::npos) << c.err;
}

// The vehicle-only options are refused on the simulated fleet, --pace on vehicles, and a key file
// that is not 32 bytes or 64 hex digits: one sentence each, exit 2, nothing written.
TEST(FleetAbortCli, VehicleOptionsAndBadKeyFilesAreRefusedInOneSentence) {
  const std::string dir = socket_dir("fleet-option-refusals");
  const std::string out = dir + "/run", key = dir + "/fleet.key";
  { std::ofstream(key) << "0011223344\n"; }
  const std::string run = "run multiplexing --world sites --drones 1 -o " + out + " ";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--signing-key " + key, "--signing-key needs --backend mavlink"},
      {"--allow-no-gcs-failsafe", "--allow-no-gcs-failsafe needs --backend mavlink"},
      {"--backend mavlink --vehicles udp:127.0.0.1:14999 --pace 2", "--pace is for --backend sim"},
      {"--backend mavlink --vehicles udp:127.0.0.1:14999 --signing-key " + key,
       key + ": a signing key is 32 bytes, or 64 hexadecimal digits (11 bytes here)"},
      {"--backend mavlink --vehicles udp:127.0.0.1:14999 --signing-key " + dir + "/none.key",
       "--signing-key " + dir + "/none.key: cannot be read"},
  };
  for (const auto& [args, sentence] : cases) {
    const CliRun r = run_swath_fleet(run + args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find(sentence), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
}

// Vehicles carry the world's fence (uploaded as an inclusion fence): a home outside it is refused
// before any link is opened (nothing listens on these ports); the simulated fleet may start there.
TEST(FleetAbortCli, AVehicleHomeOutsideTheWorldsFenceIsRefusedBeforeAnyLink) {
  const std::string dir = socket_dir("fleet-home-outside");
  const std::string out = dir + "/run";
  std::string urls;
  for (int i = 0; i < 6; ++i)
    urls += (i ? "," : "") + std::string("udp:127.0.0.1:") + std::to_string(14961 + i);
  const CliRun r = run_swath_fleet(
      "run wifi --world rf_field --drones 6 --backend mavlink --vehicles " + urls + " -o " + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("drone-6's home (30.0, 0.0) m is outside the world's fence"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(out));
  const CliRun sim = run_swath_fleet("run wifi --world rf_field --drones 6 -o " + out);
  EXPECT_EQ(sim.exit_code, 0) << sim.err;
}

}  // namespace
}  // namespace swath::test::fleet_abort
