// swath-fleet's live and replay page in a real browser (headless Chromium), checked against the
// run's events.jsonl, read here independently of the page's script:
// - the replay page (swath-fleet view): no script error, no request, as many drones as run_start
//   names, each drone's marker where the log's last position of it puts it;
// - the live page (swath-fleet run --live 0 --pace): no script error, no request but to the local
//   server, every event line received, at least one a second while the run flew (the page's own
//   per-second counter, read from its DOM);
// - events.jsonl byte-identical with and without --live; a port in use refused (exit 2).
// Without Chromium (/usr/bin/chromium or $SWATH_CHROMIUM) the browser tests skip, saying so.
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <thread>

#include <GeographicLib/LocalCartesian.hpp>

#include "chromium.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using namespace swath::html_test;

// A fresh, empty directory `name` in the scratch directory.
fs::path fresh_dir(const std::string& name) {
  const fs::path dir = scratch(name);
  fs::create_directories(dir);
  return dir;
}

const std::string kFleet = "'" SWATH_FLEET_BINARY "' ";
// A short run: two drones over the hotspot world.
const std::string kRun = "run hotspot --world hotspot --drones 2 --seed 4 ";

// Chromium headless, offline but for 127.0.0.1 (every other host name fails to resolve); the
// DOM it dumps once the page ran. `wait` is Chromium's own flags for how long.
std::string dom(const fs::path& profile, const std::string& url, const std::string& wait) {
  const std::string command = "'" + chromium() +
                              "' --headless --no-sandbox --disable-gpu --no-first-run " +
                              "--no-default-browser-check --user-data-dir='" + profile.string() +
                              "' --host-resolver-rules='MAP * ~NOTFOUND, EXCLUDE 127.0.0.1' " +
                              wait + " --dump-dom '" + url + "' 2>/dev/null";
  return run(command).out;
}

std::vector<json> events(const fs::path& run_dir) {
  std::vector<json> out;
  std::istringstream in(slurp(run_dir / "events.jsonl"));
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) out.push_back(json::parse(line));
  return out;
}

// Each drone's last logged place at or before `t_s`: its positions are drone_state and
// drone_mode (docs/swath-fleet.md; a dispatch's place is its target).
std::map<int, std::array<double, 2>> places_at(const std::vector<json>& log, double t_s) {
  std::map<int, std::array<double, 2>> last;
  for (const json& e : log)
    if (e["t_s"].get<double>() <= t_s && (e["ev"] == "drone_state" || e["ev"] == "drone_mode"))
      last[e["drone"].get<int>()] = {e["x_m"].get<double>(), e["y_m"].get<double>()};
  return last;
}

// A time as the page's address takes it, every digit (the page reads the same double).
std::string time_text(double t_s) {
  std::ostringstream s;
  s << std::setprecision(17) << t_s;
  return s.str();
}

TEST(ReplayPage, DrawsEveryDroneWhereTheLogLastPutsIt) {
  REQUIRE_CHROMIUM();
  const fs::path dir = fresh_dir("replay");
  ASSERT_EQ(run(kFleet + kRun + "-o '" + (dir / "run").string() + "'").exit_code, 0);
  const ShellRun view = run(kFleet + "view '" + (dir / "run").string() + "' -o '" +
                            (dir / "view.html").string() + "'");
  ASSERT_EQ(view.exit_code, 0) << view.out;
  // The log's own account: run_start's drones, each one's last logged place.
  const std::vector<json> log = events(dir / "run");
  ASSERT_FALSE(log.empty());
  const std::size_t drones = log.front()["drones"].size();
  ASSERT_GT(drones, 0u);
  const double end_s = log.back()["t_s"];
  // The run's end (the page opens there), and a moment mid-flight (view.html#t=SECONDS): the
  // first change of mode after a third of the run that moved a drone since its last place
  double mid_s = -1;
  for (std::size_t k = 0; k < log.size() && mid_s < 0; ++k) {
    const json& e = log[k];
    if (e["ev"] != "drone_mode" || e["t_s"].get<double>() < end_s / 3) continue;
    // ... and the drone's last word at that time (no drone_state of the same tick after it).
    if (places_at(log, e["t_s"].get<double>()).at(e["drone"].get<int>()) !=
        std::array<double, 2>{e["x_m"].get<double>(), e["y_m"].get<double>()})
      continue;
    const auto before = places_at(std::vector<json>(log.begin(), log.begin() + k), end_s);
    const auto was = before.find(e["drone"].get<int>());
    if (was != before.end() && std::hypot(was->second[0] - e["x_m"].get<double>(),
                                          was->second[1] - e["y_m"].get<double>()) > 0.1)
      mid_s = e["t_s"];
  }
  ASSERT_GT(mid_s, 0) << "no drone moved between its states";
  for (const double t_s : {end_s, mid_s}) {
    const std::string url =
        "file://" + (dir / "view.html").string() + (t_s == end_s ? "" : "#t=" + time_text(t_s));
    const json check = self_check(dom(dir / "profile", url, "--virtual-time-budget=5000"));
    ASSERT_TRUE(check.is_object()) << "no self-check in the page's DOM";
    EXPECT_EQ(check["errors"], json::array());
    EXPECT_EQ(check["foreign_requests"], json::array());
    EXPECT_EQ(check["ended"], t_s == end_s);
    EXPECT_NEAR(check["t_s"].get<double>(), t_s, 1e-9);
    EXPECT_EQ(check["drones"], drones);
    const std::map<int, std::array<double, 2>> last = places_at(log, t_s);
    ASSERT_EQ(check["positions"].size(), last.size());
    // The world's origin (share/worlds/hotspot.yaml): the page draws in lat/lon, each drone where
    // GeographicLib's tangent plane at the origin puts its local metres, within 1 cm.
    EXPECT_EQ(check["geographic"], true);
    const GeographicLib::LocalCartesian world(42.3601, -71.0942, 0);
    for (const json& p : check["positions"]) {
      const std::array<double, 2> want = last.at(p["drone"].get<int>());
      EXPECT_NEAR(p["x_m"].get<double>(), want[0], 1e-6) << "t " << t_s << ": " << p.dump();
      EXPECT_NEAR(p["y_m"].get<double>(), want[1], 1e-6) << "t " << t_s << ": " << p.dump();
      double lat, lon, h;
      world.Reverse(want[0], want[1], 0, lat, lon, h);
      EXPECT_NEAR(p["lat_deg"].get<double>(), lat, 1e-7) << "t " << t_s << ": " << p.dump();
      EXPECT_NEAR(p["lon_deg"].get<double>(), lon, 1.4e-7) << "t " << t_s << ": " << p.dump();
    }
  }
}

// Chromium headless on the wall clock (no virtual time: the page's per-second counter must count
// real seconds), driven over --remote-debugging-pipe (DevTools protocol messages, each ended by a
// NUL, on fds 3 and 4): opens `url`, then reads the page's self-check every 0.2 s until `done`
// says so of it or `timeout_s` passes; the last one read.
class PipeBrowser {
 public:
  PipeBrowser(const fs::path& profile, const std::string& url) {
    int to_browser[2], from_browser[2];
    if (::pipe(to_browser) != 0 || ::pipe(from_browser) != 0) return;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(to_browser[0], 3);
      ::dup2(from_browser[1], 4);
      const int null_fd = ::open("/dev/null", O_WRONLY);  // Chromium's chatter
      ::dup2(null_fd, 2);
      const std::string dir = "--user-data-dir=" + profile.string();
      ::execl(chromium().c_str(), "chromium", "--headless", "--no-sandbox", "--disable-gpu",
              "--no-first-run", "--no-default-browser-check", dir.c_str(),
              "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1", "--remote-debugging-pipe",
              url.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ::close(to_browser[0]);
    ::close(from_browser[1]);
    out_ = to_browser[1];
    in_ = ::fdopen(from_browser[0], "r");
  }
  ~PipeBrowser() {
    if (pid_ <= 0) return;
    call("Browser.close", json::object());
    ::close(out_);
    if (in_) std::fclose(in_);
    ::waitpid(pid_, nullptr, 0);
  }

  template <class Done>
  json self_check(double timeout_s, Done done) {
    std::string session;
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    json last;
    while (std::chrono::steady_clock::now() < end) {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      if (session.empty()) session = attach();
      if (session.empty()) continue;
      const json r =
          call("Runtime.evaluate",
               {{"expression", "(document.getElementById('swath-check') || {}).textContent"},
                {"returnByValue", true}},
               session);
      const json value = r.value("/result/result/value"_json_pointer, json());
      if (!value.is_string()) continue;
      last = json::parse(value.get<std::string>(), nullptr, false);
      if (last.is_object() && done(last)) break;
    }
    return last;
  }

 private:
  std::string attach() {
    const json targets = call("Target.getTargets", json::object());
    for (const json& t : targets.value("/result/targetInfos"_json_pointer, json::array()))
      if (t["type"] == "page") {
        const json a =
            call("Target.attachToTarget", {{"targetId", t["targetId"]}, {"flatten", true}});
        return a.value("/result/sessionId"_json_pointer, std::string());
      }
    return "";
  }
  // A command and its answer (the events read meanwhile are dropped).
  json call(const std::string& method, const json& params, const std::string& session = "") {
    json m{{"id", ++id_}, {"method", method}, {"params", params}};
    if (!session.empty()) m["sessionId"] = session;
    const std::string text = m.dump() + '\0';
    if (::write(out_, text.data(), text.size()) != static_cast<ssize_t>(text.size())) return json();
    if (method == "Browser.close") return json();
    for (std::string reply; in_;) {
      reply.clear();
      for (int c; (c = std::fgetc(in_)) != EOF && c != 0;) reply += static_cast<char>(c);
      if (reply.empty() && std::feof(in_)) return json();
      const json r = json::parse(reply, nullptr, false);
      if (r.is_object() && r.value("id", 0) == id_) return r;
    }
    return json();
  }
  pid_t pid_ = -1;
  int out_ = -1, id_ = 0;
  FILE* in_ = nullptr;
};

// A background `swath-fleet run --live 0`: its URL read from its standard error.
struct LiveRun {
  pid_t pid = -1;
  std::string url;
};

LiveRun start_live(const std::string& args, const fs::path& err) {
  LiveRun r;
  r.pid = ::fork();
  if (r.pid == 0) {
    const std::string command = kFleet + args + " 2>'" + err.string() + "' >/dev/null";
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const std::string marker = "live view at ";
  for (int k = 0; k < 200 && r.url.empty(); ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const std::string text = slurp(err);
    const std::size_t at = text.find(marker);
    if (at != std::string::npos && text.find('\n', at) != std::string::npos)
      r.url = text.substr(at + marker.size(), text.find('\n', at) - at - marker.size());
  }
  return r;
}

int wait_exit(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(LivePage, ReceivesAnUpdateEverySecondOfAPacedRun) {
  REQUIRE_CHROMIUM();
  const fs::path dir = fresh_dir("live");
  // The run flies at PACE times the wall clock; the page is opened as it starts.
  const LiveRun live =
      start_live(kRun + "--pace 20 --live 0 --live-linger 3 -o '" + (dir / "run").string() + "'",
                 dir / "err.txt");
  ASSERT_FALSE(live.url.empty()) << slurp(dir / "err.txt");
  EXPECT_EQ(live.url.rfind("http://127.0.0.1:", 0), 0u) << live.url;
  const auto t0 = std::chrono::steady_clock::now();
  json check;
  {
    PipeBrowser browser(dir / "profile", live.url);
    check = browser.self_check(60, [](const json& c) { return c.value("ended", false); });
  }
  const double browser_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(wait_exit(live.pid), 0) << slurp(dir / "err.txt");
  ASSERT_TRUE(check.is_object()) << "no self-check in the page's DOM";
  EXPECT_EQ(check["errors"], json::array());
  EXPECT_EQ(check["foreign_requests"], json::array());
  EXPECT_EQ(check["ended"], true);
  EXPECT_EQ(check["geographic"], true);  // the world's origin, from the server's page
  const std::vector<json> logged = events(dir / "run");
  EXPECT_EQ(check["messages"], logged.size());
  // Every whole second from the first message to the last: at least one message.
  const json& per_second = check["per_second"];
  ASSERT_GE(per_second.size(), 3u) << "the run was over too soon to tell: " << per_second.dump();
  for (std::size_t s = 0; s + 1 < per_second.size(); ++s)
    EXPECT_GE(per_second[s].get<int>(), 1) << "second " << s << ": " << per_second.dump();
  std::cout << "live page: " << check["messages"] << " messages over " << per_second.size()
            << " s, " << per_second.dump() << "; browser " << browser_s << " s\n";
}

TEST(LivePage, EventsAreTheSameBytesWithAndWithoutLive) {
  const fs::path dir = fresh_dir("same");
  ASSERT_EQ(run(kFleet + kRun + "-o '" + (dir / "plain").string() + "'").exit_code, 0);
  const ShellRun live =
      run(kFleet + kRun + "--live 0 --live-linger 0 -o '" + (dir / "live").string() + "'");
  ASSERT_EQ(live.exit_code, 0) << live.out;
  EXPECT_NE(live.out.find("live view at http://127.0.0.1:"), std::string::npos) << live.out;
  const std::string plain = slurp(dir / "plain" / "events.jsonl");
  EXPECT_GT(plain.size(), 1000u);
  EXPECT_TRUE(plain == slurp(dir / "live" / "events.jsonl"));
}

TEST(LivePage, APortInUseIsRefused) {
  const fs::path dir = fresh_dir("port");
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  ASSERT_EQ(::listen(fd, 1), 0);
  socklen_t size = sizeof addr;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &size);
  const std::string port = std::to_string(ntohs(addr.sin_port));
  const ShellRun refused =
      run(kFleet + kRun + "--live " + port + " -o '" + (dir / "run").string() + "'");
  ::close(fd);
  EXPECT_EQ(refused.exit_code, 2) << refused.out;
  EXPECT_NE(refused.out.find("127.0.0.1:" + port + " is in use"), std::string::npos) << refused.out;
  EXPECT_EQ(std::count(refused.out.begin(), refused.out.end(), '\n'), 1) << refused.out;
  EXPECT_FALSE(fs::exists(dir / "run"));
}

}  // namespace
