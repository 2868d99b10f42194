#include "run_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <system_error>
#include <thread>

#include "fleet_images.hpp"
#include "intervals.hpp"
#include "live_server.hpp"
#include "map_furniture.hpp"
#include "run_control.hpp"
#include "seed_option.hpp"
#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/output_set.hpp"
#include "swath/fleet/apps.hpp"
#include "swath/fleet/event_check.hpp"
#include "swath/fleet/event_replay.hpp"
#include "swath/fleet/mavlink_fleet.hpp"

#include <filesystem>
#include <fstream>

#include "swath/mavlink/signing.hpp"
#include "swath/web/live_page.hpp"

namespace swath::apps {

using base::InputError;
using json = nlohmann::ordered_json;

void FleetRunCommand::setup(CLI::App& app) {
  add_fleet_options(app, request_, true);
  app.add_option("-o,--output", output_, "Directory for the run's files")->required();
  app.add_flag("--render", render_, "Also draw tracks.png and gantt.png");
  app.add_option("--size", size_, "Size of the pictures, WxH pixels")->capture_default_str();
  app.add_option("--backend", backend_,
                 "sim: the simulated fleet; mavlink: the fleet's drones are vehicles over "
                 "MAVLink (--vehicles, or the fleet file's mavlink {url, sysid} per drone), "
                 "flown on the wall clock: ArduCopter, or PX4 when its HEARTBEAT says so (the "
                 "PX4 driver is UNTESTED on PX4: written from its documentation; a warning "
                 "names each PX4 vehicle); each vehicle's lost-link failsafe parameters are read "
                 "at connect: off, the vehicle is refused take-off (see "
                 "--allow-no-gcs-failsafe)")
      ->check(CLI::IsMember({"sim", "mavlink"}))
      ->capture_default_str();
  app.add_option(
      "--vehicles", vehicles_,
      "With --backend mavlink: one vehicle per drone of the fleet, in order, "
      "comma-separated: udp:HOST:PORT listens there for a vehicle sending to it "
      "(--out udp:HOST:PORT), tcp:HOST:PORT connects to it (SITL: 5760 + 10 x "
      "instance); /SYSID after the port (1..255, default: its place + 1); overrides the fleet "
      "file's mavlink {url, sysid}");
  world_seed_option_ =
      app.add_option(
             "--world-seed", world_seed_,
             "Draw the world's random parts from this seed instead of the file's (the scenarios of "
             "compare and tune, as `worlds gen KIND --seed N` prints them)")
          ->check(seed_check());
  app.add_option("--on-abort", on_abort_,
                 "What SIGINT, SIGTERM or an unexpected error tells every airborne vehicle before "
                 "the run ends and its files are written: rtl (return to launch) or land (where "
                 "it is)")
      ->check(CLI::IsMember({"rtl", "land"}))
      ->capture_default_str();
  app.add_option("--ctl-socket", ctl_socket_,
                 "Listen for `swath-fleet ctl` orders (pause, resume, rtl-all, land-all) on this "
                 "Unix socket, made with mode 0600 (its directory must be yours and closed to "
                 "others, e.g. $XDG_RUNTIME_DIR/swath-fleet.sock) and removed at the end");
  app.add_flag("--allow-no-gcs-failsafe", allow_no_gcs_failsafe_,
               "With --backend mavlink: let vehicles whose lost-link failsafe reads as off "
               "(ArduCopter FS_GCS_ENABLE 0, PX4 NAV_DLL_ACT 0) take off, with a warning");
  app.add_option("--signing-key", signing_key_,
                 "With --backend mavlink: sign every frame sent with MAVLink 2 signing and read "
                 "only frames signed with this key; FILE holds the 32-byte secret, raw or as 64 "
                 "hexadecimal digits (e.g. from `openssl rand -hex 32`)");
  live_option_ = app.add_option("--live", live_,
                                "Serve a live page of the run on http://127.0.0.1:PORT/ (default "
                                "port 8765; 0: any free port; the URL is printed on stderr): "
                                "drones, tasks, forecasts and assignments as they happen; put it "
                                "after APP")
                     ->expected(0, 1)
                     ->option_text("[PORT]");
  app.add_option("--live-linger", live_linger_s_,
                 "With --live: keep serving this many seconds after the run has ended (default: "
                 "until Ctrl-C)")
      ->check(CLI::NonNegativeNumber)
      ->option_text("S");
  app.add_option("--pace", pace_,
                 "With --backend sim: fly the simulation at FACTOR times the wall clock (1: real "
                 "time), so that ctl orders and signals come mid-run; default 0: as fast as it "
                 "computes")
      ->check(CLI::Range(0.0, 1e6));
}

// The vehicles of --backend mavlink: --vehicles when given (it overrides the fleet file), else
// every drone's `mavlink {url, sysid}` from the fleet file, in fleet order.
namespace {
std::vector<fleet::VehicleAddress> vehicle_urls(const std::string& vehicles,
                                                const std::string& fleet_file,
                                                const PreparedRun& p) {
  if (!vehicles.empty()) {
    const auto urls = fleet::parse_vehicle_addresses(vehicles);
    if (urls.size() != p.drones.size())
      throw InputError("--vehicles names " + std::to_string(urls.size()) +
                       " vehicles for a fleet of " + std::to_string(p.drones.size()) + " drones");
    return urls;
  }
  std::vector<fleet::VehicleAddress> urls;
  std::string missing;
  int without = 0;
  for (const fleet::DroneSpec& d : p.drones) {
    if (d.vehicle) {
      urls.push_back(*d.vehicle);
    } else {
      missing += (missing.empty() ? "" : ", ") + d.drone.name;
      ++without;
    }
  }
  if (urls.empty())
    throw InputError(
        "--backend mavlink needs --vehicles, or a mavlink {url, sysid} for every "
        "drone of the fleet file");
  if (without > 0)
    throw InputError(fleet_file + ": " + missing + (without == 1 ? " has" : " have") +
                     " no mavlink {url, sysid} while " + std::to_string(urls.size()) + " of the " +
                     std::to_string(p.drones.size()) +
                     " drones do; give every drone one, or give --vehicles");
  return urls;
}
}  // namespace

namespace {
// --signing-key FILE: its bytes (a key is 32 raw bytes or 64 hex digits: anything over 1 KiB is
// not one).
mavlink::SigningKey read_signing_key(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("--signing-key " + path + ": cannot be read");
  std::string contents(1025, '\0');
  in.read(contents.data(), static_cast<std::streamsize>(contents.size()));
  contents.resize(static_cast<std::size_t>(in.gcount()));
  return mavlink::parse_signing_key(contents, path);
}

// A run on the wall clock (--pace, or vehicles) says on stderr when each drone is first seen off
// the ground (above 0.5 m in a drone_mode or drone_state event): a person (or a test) sees the
// fleet airborne before stopping it. The names come from the fleet.
constexpr double kAirborneAboveM = 0.5;
std::function<void(const std::string&)> airborne_reporter(std::vector<std::string> names) {
  std::vector<bool> seen(names.size());  // before the names move into the closure
  return [names = std::move(names), seen = std::move(seen)](const std::string& line) mutable {
    if (line.find("\"drone_mode\"") == std::string::npos &&
        line.find("\"drone_state\"") == std::string::npos)
      return;
    const nlohmann::json e = nlohmann::json::parse(line);
    const int drone = e.value("drone", -1);
    if (drone < 0 || static_cast<std::size_t>(drone) >= names.size() || seen[drone]) return;
    // A vehicle on its pad reports a few millimetres, or centimetres, either way.
    if (!(e.value("alt_m", 0.0) > kAirborneAboveM)) return;
    seen[drone] = true;
    std::cerr << "swath-fleet run: " << names[drone] << " airborne at "
              << base::fixed_text(e.value("t_s", 0.0), 1) << " s\n";
  };
}

// The run was aborted; its files are written. Exit 128 + the signal (130 SIGINT, 143 SIGTERM) as
// a shell reports a program a signal ended, 4 for a ctl order, 1 for an unexpected error.
int aborted_exit(const fleet::RunRecord& r, int signal_number, fleet::AbortAction on_abort,
                 const std::string& output) {
  const bool land = r.aborted == "ctl land-all" ||
                    (r.aborted != "ctl rtl-all" && on_abort == fleet::AbortAction::land);
  std::cerr << "swath-fleet run: aborted (" << r.aborted << "): every airborne vehicle was told to "
            << (land ? "land where it is" : "return to launch") << "; the run's files are in "
            << output << "\n";
  if (r.aborted_by_error) return base::kExitFailure;
  if (r.aborted == "SIGINT" || r.aborted == "SIGTERM") return 128 + signal_number;
  return base::kExitNotCompleted;
}
}  // namespace

// --live: the server, started before the run so that a taken port is refused before anything
// happens; the run hands it each event line (it changes nothing of the run).
std::unique_ptr<LiveServer> FleetRunCommand::start_live(fleet::RuntimeSettings& settings) const {
  if (live_option_->count() == 0) {
    if (live_linger_s_ >= 0) throw InputError("--live-linger needs --live");
    return nullptr;
  }
  std::optional<web::MapOrigin> origin;  // the world's: the page draws in lat/lon
  if (settings.origin) origin = web::MapOrigin{settings.origin->lat_deg, settings.origin->lon_deg};
  auto server = std::make_unique<LiveServer>(live_port(live_), web::live_page(output_, origin));
  // After any listener already set (the airborne reporter of a wall-clock run).
  settings.on_event = [s = server.get(),
                       before = std::move(settings.on_event)](const std::string& line) {
    if (before) before(line);
    s->append(line);
  };
  std::cerr << "swath-fleet run: live view at " << server->url() << "\n";
  return server;
}

// After the run: the page may still be reading (a simulated run is over in moments).
void FleetRunCommand::linger(const LiveServer& server, const RunControl& control) const {
  std::cerr << "swath-fleet run: the run has ended; its live view stays at " << server.url()
            << (live_linger_s_ < 0 ? " until Ctrl-C"
                                   : " for " + base::fixed_text(live_linger_s_, 1) + " s")
            << "\n";
  const auto end = std::chrono::steady_clock::now() +
                   std::chrono::duration<double>(live_linger_s_ < 0 ? 1e9 : live_linger_s_);
  while (control.signal_number() == 0 && std::chrono::steady_clock::now() < end)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
}

int FleetRunCommand::run() {
  const auto [width_px, height_px] = parse_size(size_);
  PreparedRun p =
      world_seed_option_->count() > 0 ? prepare_run(request_, world_seed_) : prepare_run(request_);
  if (pace_ > 0 && backend_ == "mavlink")
    throw InputError("--pace is for --backend sim (vehicles fly on the wall clock)");
  // Refused now, not after a flight whose record would then have nowhere to go.
  base::check_output_names(output_, "fleet-run", run_file_names(render_));
  std::unique_ptr<fleet::MavlinkFleet> vehicles;
  const RunControl* control_made = nullptr;  // once made: a signal cuts the final wait short
  if (backend_ == "mavlink") {
    const std::vector<fleet::VehicleAddress> urls = vehicle_urls(vehicles_, request_.fleet, p);
    fleet::MavlinkFleetSettings settings;
    settings.origin = p.world->origin;
    settings.fence_m = p.world->fence();
    // Checked again by the runtime; here before any vehicle link is opened.
    fleet::LocalEnvelope world_fence;
    if (settings.fence_m.size() >= 3) world_fence.inclusions.push_back(settings.fence_m);
    for (const fleet::DroneSpec& d : p.drones)
      if (!world_fence.refusal_xy(d.home_m.x, d.home_m.y).empty())
        throw InputError(d.drone.name + "'s home (" + base::fixed_text(d.home_m.x, 1) + ", " +
                         base::fixed_text(d.home_m.y, 1) +
                         ") m is outside the world's fence, which the vehicles carry: give homes "
                         "inside it (a fleet file's home_m)");
    // The fleet file's fence polygons too: every one is uploaded, read back and checked.
    settings.inclusions_m = p.settings.envelope.inclusions;
    settings.exclusions_m = p.settings.envelope.exclusions;
    settings.wall_clock = true;
    settings.allow_no_gcs_failsafe = allow_no_gcs_failsafe_;
    settings.stop_waiting = [&control_made] {
      return control_made != nullptr && control_made->signal_number() != 0;
    };
    if (!signing_key_.empty()) settings.signing_key = read_signing_key(signing_key_);
    try {
      vehicles = fleet::open_mavlink_fleet(urls, settings);
    } catch (const std::system_error& e) {
      throw InputError(std::string("--vehicles: ") + e.what());
    }
    p.settings.backend = vehicles.get();
    std::cerr << "swath-fleet run: " << urls.size()
              << " vehicles over MAVLink on the wall clock; when the app ends, each is sent home "
                 "and waited for (up to "
              << base::fixed_text(settings.end_timeout_s, 0) << " s) until it has landed\n";
    p.vehicles = urls;
  } else if (!vehicles_.empty()) {
    throw InputError("--vehicles needs --backend mavlink");
  } else if (allow_no_gcs_failsafe_) {
    throw InputError("--allow-no-gcs-failsafe needs --backend mavlink");
  } else if (!signing_key_.empty()) {
    throw InputError("--signing-key needs --backend mavlink");
  }
  p.settings.pace = pace_;
  p.settings.on_abort = on_abort_ == "land" ? fleet::AbortAction::land : fleet::AbortAction::rtl;
  RunControl control(p.settings.on_abort, ctl_socket_);
  control_made = &control;
  p.settings.control = [&control] { return control.poll(); };
  p.settings.abort_pending = [&control] { return control.signal_number() != 0; };
  if (pace_ > 0 || backend_ == "mavlink") {
    std::vector<std::string> names;
    for (const auto& d : p.drones) names.push_back(d.drone.name);
    p.settings.on_event = airborne_reporter(std::move(names));
  }
  std::unique_ptr<LiveServer> live = start_live(p.settings);
  const fleet::RunRecord r = fleet::run_app(p.app, *p.world, p.drones, p.settings);
  // Aborted: a second signal must not cost the run its record (it waits until the files are in).
  if (!r.aborted.empty()) control.hold_signals();
  base::OutputSet set(output_, "fleet-run");
  add_run_files(set, p, r);
  if (render_) {
    // Drawn from the run as events.jsonl records it (times rounded as written), so that `render`
    // redraws the same bytes (exact-area anti-aliasing shows any sub-pixel shift of a bar edge).
    const fleet::RunRecord drawn = fleet::replay_record(r.events_jsonl, "events.jsonl");
    const FleetPicture tracks = tracks_picture(*p.world, drawn, width_px, height_px);
    set.add("tracks.png", render::encode_png(render::draw(tracks.scene, tracks.view)));
    const FleetPicture gantt = gantt_picture(drawn, width_px, std::max(200, height_px / 3));
    set.add("gantt.png", render::encode_png(render::draw(gantt.scene, gantt.view)));
  }
  set.commit();
  if (live && r.aborted.empty()) linger(*live, control);
  if (!r.aborted.empty())
    return aborted_exit(r, control.signal_number(), p.settings.on_abort, output_);
  if (r.completed) {
    std::cout << request_.app << " completed in " << base::fixed_text(r.completion_time_s, 1)
              << " s with " << p.drones.size() << " drone" << (p.drones.size() == 1 ? "" : "s")
              << " (" << p.settings.scheduler << ")\n";
    return base::kExitSuccess;
  }
  std::cerr << "swath-fleet run: " << request_.app << " did not complete: " << r.failure
            << " (files written to " << output_ << ")\n";
  return base::kExitNotCompleted;
}

namespace {
// An event of a run's log is short: run_start of the largest fleet (100 drones) is a few kB. A
// longer line is refused before it is parsed, so that a log declaring millions of drones or
// tasks on one line cannot take gigabytes.
constexpr std::size_t kMaxEventLineBytes = std::size_t{1} << 20;

std::string read_event_log(const std::string& path) {
  std::string text = base::read_text_file(path, "event log");
  std::size_t start = 0;
  for (long long line = 1; start < text.size(); ++line) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    if (end - start > kMaxEventLineBytes)
      throw InputError(path + ": line " + std::to_string(line) + ": an event of " +
                       std::to_string(end - start) +
                       " bytes; an event of swath-fleet is at most 1 MiB (a fleet of at most "
                       "100 drones)");
    start = end + 1;
  }
  return text;
}
}  // namespace

void FleetCheckCommand::setup(CLI::App& app) {
  app.add_option("RUN", run_, "A run's directory (or its events.jsonl)")->required();
}

int FleetCheckCommand::run() {
  std::string path = run_;
  if (std::filesystem::is_directory(path)) path += "/events.jsonl";
  const fleet::EventCheck c = fleet::check_events(read_event_log(path));
  for (const auto& v : c.violations)
    std::cout << path << ": line " << v.line << ": " << v.rule << ": " << v.message << "\n";
  std::cout << path << ": " << c.lines << " events, " << c.tasks << " tasks (";
  bool first = true;
  for (const auto& [k, n] : c.terminal)
    std::cout << (first ? "" : ", ") << n << " " << k.substr(5), first = false;
  std::cout << "), " << c.results << " results, " << c.duplicates << " duplicates dropped, "
            << c.faults << " faults: "
            << (c.ok() ? "every rule holds" : std::to_string(c.violations.size()) + " violations")
            << "\n";
  return c.ok() ? base::kExitSuccess : base::kExitNotCompleted;
}

void FleetRenderCommand::setup(CLI::App& app) {
  app.add_option("RUN", run_, "A run's directory (run -o DIR)")->required();
  app.add_option("--world", world_,
                 "The world file, when it is no longer where summary.json's world_file says");
  app.add_option("-o,--output", output_, "Where to write the pictures (default: RUN)");
  app.add_option("--size", size_, "Size of the pictures, WxH pixels")->capture_default_str();
}

int FleetRenderCommand::run() {
  const auto [width_px, height_px] = parse_size(size_);
  const std::string events_path = run_ + "/events.jsonl", summary_path = run_ + "/summary.json";
  const fleet::RunRecord r = fleet::replay_record(read_event_log(events_path), events_path);
  const nlohmann::json summary = base::parse_json_document(
      base::read_text_file(summary_path, "run summary", base::kMaxConfigFileBytes), summary_path);
  std::string world_file = world_;
  if (world_file.empty()) {
    if (!summary.contains("world_file") || !summary["world_file"].is_string())
      throw InputError(summary_path + ": no world_file; give --world");
    world_file = summary["world_file"];
  }
  std::optional<std::uint64_t> seed;
  if (summary.contains("world_seed") && summary["world_seed"].is_number_unsigned())
    seed = summary["world_seed"].get<std::uint64_t>();
  const auto world = worlds::parse_world(
      base::read_text_file(world_file, "world file", base::kMaxConfigFileBytes), world_file, seed);
  const bool in_place = output_.empty() || std::filesystem::equivalent(output_, run_);
  base::OutputSet set(in_place ? run_ : output_, in_place ? "fleet-run" : "fleet-render",
                      {in_place ? base::OutputSet::Mode::amend : base::OutputSet::Mode::replace});
  const FleetPicture tracks = tracks_picture(*world, r, width_px, height_px);
  set.add("tracks.png", render::encode_png(render::draw(tracks.scene, tracks.view)));
  const FleetPicture gantt = gantt_picture(r, width_px, std::max(200, height_px / 3));
  set.add("gantt.png", render::encode_png(render::draw(gantt.scene, gantt.view)));
  set.commit();
  std::cout << "swath-fleet render: " << r.drones.size()
            << (r.drones.size() == 1 ? " drone over " : " drones over ")
            << base::fixed_text(r.end_s, 1) << " s -> " << (in_place ? run_ : output_)
            << "/tracks.png, gantt.png\n";
  return base::kExitSuccess;
}

void FleetWorldsCommand::setup(CLI::App& app) {
  app.add_option("ACTION", action_, "gen")->required();
  app.add_option("KIND", kind_, "hotspot, road, rf_field, sites or tracking")->required();
  app.add_option("--seed", seed_, "The world's seed")->check(seed_check())->capture_default_str();
}

int FleetWorldsCommand::run() {
  if (action_ != "gen")
    throw InputError("worlds: unknown action \"" + action_ + "\"; use: worlds gen KIND");
  const std::string path = world_path(kind_);
  const auto w = worlds::parse_world(base::read_text_file(path, "world file"), path, seed_);
  // The bundled file with its seed replaced, then the drawn parts, written out.
  std::istringstream in(base::read_text_file(path, "world file"));
  std::ostringstream out;
  out << "# swath-fleet worlds gen " << kind_ << " --seed " << seed_ << "\n";
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("seed:", 0) == 0) continue;
    if (line.rfind("#", 0) == 0) continue;
    out << line << "\n";
  }
  out << "seed: " << seed_ << "\n";
  // Exact: the printed world is the one compare and tune draw for this seed.
  auto num = [](double v) { return base::shortest_text(v); };
  if (const auto* h = dynamic_cast<const worlds::HotspotWorld*>(w.get())) {
    out << "source: {x_m: " << num(h->source_m.x) << ", y_m: " << num(h->source_m.y) << "}\n";
  } else if (const auto* r = dynamic_cast<const worlds::RoadWorld*>(w.get())) {
    if (path.find("road") != std::string::npos &&
        base::read_text_file(path, "world file").find("road:") == std::string::npos) {
      out << "road:\n";
      for (const auto& p : r->road_m) out << "  - [" << num(p[0]) << ", " << num(p[1]) << "]\n";
    }
  } else if (const auto* s = dynamic_cast<const worlds::SitesWorld*>(w.get())) {
    out << "sites:\n";
    for (const auto& [n, p] : s->sites)
      out << "  " << n << ": {x_m: " << num(p.x) << ", y_m: " << num(p.y) << "}\n";
  }
  std::cout << out.str();
  return base::kExitSuccess;
}

int FleetAppsCommand::run() {
  for (const fleet::App& a : fleet::all_apps())
    std::cout << a.name << "\t" << a.description << "\n";
  return base::kExitSuccess;
}

void FleetCompareCommand::setup(CLI::App& app) {
  add_fleet_options(app, request_, false);
  app.add_option("--schedulers", schedulers_, "Comma-separated schedulers to compare")
      ->capture_default_str();
  app.add_option("--seeds", seeds_, "Seeds (scenarios) per scheduler")
      ->check(CLI::Range(2, 10000))
      ->capture_default_str();
  app.add_option("--histories", histories_,
                 "predictive: how many reactive runs of the other seeds GMF learns from")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  app.add_option("-o,--output", output_, "Directory for compare.csv and summary.json")->required();
}

namespace {
// The DTGs predictive's seed k learns from: reactive's runs on the next `count` seeds (cyclic),
// never its own (leave one out: the run forecast is not in its history).
std::vector<fleet::Dtg> histories_for(const std::vector<fleet::Dtg>& reactive, std::size_t k,
                                      std::size_t count) {
  std::vector<fleet::Dtg> out;
  for (std::size_t i = 1; i < reactive.size() && out.size() < count; ++i)
    out.push_back(reactive[(k + i) % reactive.size()]);
  return out;
}

using SeedRuns = std::map<std::uint64_t, TimeObservation>;

// compare.csv: a row per run; a censored run's time is in censored_at_s (its end), not in
// completion_time_s.
std::string compare_csv(const std::vector<std::string>& names,
                        std::map<std::string, SeedRuns>& runs_of) {
  std::string csv = "scheduler,seed,completed,completion_time_s,censored_at_s\n";
  for (const std::string& name : names)
    for (const auto& [seed, o] : runs_of[name])
      csv += name + "," + std::to_string(seed) + "," + (o.completed ? "true," : "false,") +
             (o.completed ? base::fixed_text(o.time_s, 3) + ","
                          : "," + base::fixed_text(o.time_s, 3)) +
             "\n";
  return csv;
}

struct SchedulerSummary {
  std::size_t runs = 0, censored = 0;
  std::vector<double> completed_s;
  std::optional<double> median_s;  ///< Kaplan–Meier
  double lower_bound_mean_s = 0;   ///< censored runs counted at their end
};

SchedulerSummary summarise(const SeedRuns& runs) {
  SchedulerSummary s;
  std::vector<TimeObservation> all;
  for (const auto& [seed, o] : runs) {
    all.push_back(o);
    if (o.completed)
      s.completed_s.push_back(o.time_s);
    else
      ++s.censored;
    s.lower_bound_mean_s += o.time_s;
  }
  s.runs = all.size();
  if (s.runs > 0) s.lower_bound_mean_s /= static_cast<double>(s.runs);
  s.median_s = kaplan_meier_median_s(all);
  return s;
}

double round3(double v) {
  return std::round(v * 1e3) / 1e3;
}

json scheduler_json(const std::string& name, const SchedulerSummary& s) {
  json row{{"scheduler", name},
           {"runs", s.runs},
           {"completed", s.completed_s.size()},
           {"censored", s.censored}};
  if (s.completed_s.size() >= 2) {  // over the completed runs only
    const Interval i = mean_interval95(s.completed_s);
    row["completion_time_s_mean"] = round3(i.mean);
    row["completion_time_s_ci95"] = round3(i.half);
  }
  row["completion_time_s_km_median"] = s.median_s ? json(round3(*s.median_s)) : json(nullptr);
  row["completion_time_s_mean_lower_bound"] = round3(s.lower_bound_mean_s);
  return row;
}

std::string scheduler_line(const std::string& name, const SchedulerSummary& s) {
  std::ostringstream out;
  out << name << ": " << s.completed_s.size() << "/" << s.runs << " completed";
  if (s.censored > 0) out << ", " << s.censored << " censored (ended without completing)";
  if (s.completed_s.size() >= 2) {
    const Interval i = mean_interval95(s.completed_s);
    out << (s.censored > 0 ? "; completed runs " : ", completion ") << base::fixed_text(i.mean, 1)
        << " ± " << base::fixed_text(i.half, 1) << " s (95 %)";
  }
  if (s.median_s)
    out << "; Kaplan–Meier median " << base::fixed_text(*s.median_s, 1) << " s";
  else
    out << "; Kaplan–Meier median unknown (over half the runs censored)";
  return out.str();
}

json paired_json(const std::string& name, const std::string& versus, const SeedRuns& first,
                 const SeedRuns& other) {
  json per_seed = json::array();
  std::vector<double> changes;
  int faster = 0, slower = 0, equal = 0, unknown = 0;
  for (const auto& [seed, a] : first) {
    const auto it = other.find(seed);
    if (it == other.end()) continue;
    const PairedRuns p = pair_runs(a, it->second);
    std::string sign = "unknown";
    if (p.known) sign = p.sign < 0 ? "faster" : (p.sign > 0 ? "slower" : "equal");
    (sign == "faster" ? faster : sign == "slower" ? slower : sign == "equal" ? equal : unknown)++;
    if (p.relative_change) changes.push_back(*p.relative_change);
    per_seed.push_back(
        json{{"seed", seed},
             {"relative_change",
              p.relative_change ? json(std::round(*p.relative_change * 1e5) / 1e5) : json(nullptr)},
             {"sign", sign}});
  }
  json out{{"scheduler", name},        {"versus", versus},
           {"seeds", per_seed.size()}, {"both_completed", changes.size()},
           {"faster", faster},         {"slower", slower},
           {"equal", equal},           {"unknown", unknown}};
  if (changes.size() >= 2) {  // over the seeds both completed
    const Interval i = mean_interval95(changes);
    out["relative_change_mean"] = std::round(i.mean * 1e5) / 1e5;
    out["relative_change_ci95"] = std::round(i.half * 1e5) / 1e5;
  }
  out["per_seed"] = per_seed;
  return out;
}

std::string paired_line(const json& p) {
  std::ostringstream out;
  out << p["scheduler"].get<std::string>() << " vs " << p["versus"].get<std::string>() << ", "
      << p["seeds"].get<std::size_t>() << " seeds paired: " << p["faster"].get<int>() << " faster, "
      << p["slower"].get<int>() << " slower";
  if (p["equal"].get<int>() > 0) out << ", " << p["equal"].get<int>() << " equal";
  if (p["unknown"].get<int>() > 0)
    out << ", " << p["unknown"].get<int>() << " unknown (both censored, or censored first)";
  if (p.contains("relative_change_mean"))
    out << "; change where both completed (" << p["both_completed"].get<std::size_t>()
        << "): " << base::fixed_text(100 * p["relative_change_mean"].get<double>(), 1) << " ± "
        << base::fixed_text(100 * p["relative_change_ci95"].get<double>(), 1) << " % (95 %)";
  return out.str();
}

}  // namespace

int FleetCompareCommand::run() {
  const std::vector<std::string> names = comma_names(schedulers_);
  if (names.empty()) throw InputError("--schedulers names no scheduler");
  for (const std::string& n : names)
    if (n != "predictive" && !fleet::make_scheduler(n == "reactive" ? "sa" : n))
      throw InputError("--schedulers: unknown scheduler \"" + n +
                       "\": use predictive, reactive, sa, greedy, round-robin or hungarian");
  if (request_.seed > kMaxSeed - static_cast<std::uint64_t>(seeds_ - 1))
    throw InputError("--seed " + std::to_string(request_.seed) + " --seeds " +
                     std::to_string(seeds_) + ": the last seed would be beyond 9007199254740991");
  PreparedRun check = prepare_run(request_);  // every input read before any run
  // A file of the user's in the way is refused before the runs, not after them.
  base::check_output_names(output_, "fleet-compare", {"compare.csv", "summary.json"});
  // predictive = sa + GMF (+ q) + relief with the default or --weights weights, its histories the
  // reactive runs of the other seeds: those run first.
  const bool predictive = std::find(names.begin(), names.end(), "predictive") != names.end();
  std::vector<std::string> order = names;
  if (predictive) {
    order.erase(std::remove(order.begin(), order.end(), "predictive"), order.end());
    if (std::find(order.begin(), order.end(), "reactive") == order.end())
      order.push_back("reactive");
    order.push_back("predictive");
  }
  // Each scheduler's runs by seed: a run that did not complete is censored at its end.
  std::map<std::string, std::map<std::uint64_t, TimeObservation>> runs_of;
  std::vector<fleet::Dtg> reactive_dtgs;
  int incomplete = 0;
  for (const std::string& name : order)
    for (int k = 0; k < seeds_; ++k) {
      FleetRequest r = request_;
      r.scheduler = name == "predictive" ? "sa" : name;
      r.seed = request_.seed + static_cast<std::uint64_t>(k);
      PreparedRun p = prepare_run(r, r.seed);
      if (name == "predictive") {
        p.settings.forecaster = "gmf";
        p.settings.relief = true;
        p.settings.histories =
            histories_for(reactive_dtgs, static_cast<std::size_t>(k), histories_);
      }
      const fleet::RunRecord rec = fleet::run_app(p.app, *p.world, p.drones, p.settings);
      if (name == "reactive") reactive_dtgs.push_back(fleet::parse_dtg(rec.dtg_json, "dtg.json"));
      if (std::find(names.begin(), names.end(), name) == names.end()) continue;  // history only
      runs_of[name][r.seed] = {rec.completed ? rec.completion_time_s : rec.end_s, rec.completed};
      if (!rec.completed) ++incomplete;
    }
  const std::string csv = compare_csv(names, runs_of);
  json rows = json::array();
  for (const std::string& name : names) {
    const SchedulerSummary s = summarise(runs_of[name]);
    rows.push_back(scheduler_json(name, s));
    std::cout << scheduler_line(name, s) << "\n";
  }
  // Paired against the first scheduler seed by seed (same seeds, same scenarios); every seed
  // kept, a censored side giving the sign of the change when it is known.
  json paired = json::array();
  for (std::size_t j = 1; j < names.size(); ++j) {
    paired.push_back(paired_json(names[j], names[0], runs_of[names[0]], runs_of[names[j]]));
    std::cout << paired_line(paired.back()) << "\n";
  }
  base::OutputSet set(output_, "fleet-compare");
  set.add("compare.csv", csv);
  set.add("summary.json", json{{"app", request_.app},
                               {"world", check.world->kind()},
                               {"drones", check.drones.size()},
                               {"first_seed", request_.seed},
                               {"schedulers", rows},
                               {"paired", paired}}
                                  .dump(2) +
                              "\n");
  set.commit();
  return incomplete > 0 ? base::kExitNotCompleted : base::kExitSuccess;
}

}  // namespace swath::apps
