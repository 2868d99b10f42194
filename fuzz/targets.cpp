#include "targets.hpp"

#include <CLI/CLI.hpp>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>
#include <vector>

#include "coverage_image.hpp"
#include "mission_config.hpp"
#include "plan_command.hpp"
#include "shell_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"
#include "swath/control/ardupilot_json.hpp"
#include "swath/control/config.hpp"
#include "swath/control/logistic.hpp"
#include "swath/control/mission.hpp"
#include "swath/energy/budget.hpp"
#include "swath/energy/plan.hpp"
#include "swath/energy/sim_config.hpp"
#include "swath/fleet/event_check.hpp"
#include "swath/fleet/event_replay.hpp"
#include "swath/fleet/faults.hpp"
#include "swath/fleet/fleet_file.hpp"
#include "swath/fleet/forecaster.hpp"
#include "swath/fleet/trace_replay.hpp"
#include "swath/geometry/area_facts.hpp"
#include "swath/geometry/field.hpp"
#include "swath/geometry/ground.hpp"
#include "swath/mavlink/frame.hpp"
#include "swath/planning/camera.hpp"
#include "swath/planning/plan_features.hpp"
#include "swath/render/image.hpp"
#include "swath/vehicle/drone.hpp"
#include "swath/vehicle/fleet_file.hpp"
#include "swath/vehicle/vehicle_files.hpp"
#include "swath/worlds/worlds.hpp"

namespace swath::fuzz {
namespace {

// A POSIX shell's reading of one line into words (quote removal; no expansions: a word holding
// one of $ ` * ? [ ~ unquoted, or an operator, fails the target, since the shell would act on
// it). Written from the standard, not from shell_word(): the fuzzer checks one against the other.
std::vector<std::string> shell_words_of(const std::string& line) {
  std::vector<std::string> words;
  std::string word;
  bool in_word = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == ' ' || c == '\t') {
      if (in_word) words.push_back(word), word.clear(), in_word = false;
    } else if (c == '\'') {
      const std::size_t close = line.find('\'', i + 1);
      if (close == std::string::npos) std::abort();  // unterminated quote: the shell reads on
      word += line.substr(i + 1, close - i - 1), i = close, in_word = true;
    } else if (c == '\\') {
      if (i + 1 == line.size()) std::abort();
      word += line[++i], in_word = true;
    } else if (std::string_view("$`*?[~#\"|&;<>(){}!").find(c) != std::string_view::npos &&
               !(c == '#' && in_word) && !(c == '~' && in_word)) {
      std::abort();  // a character the shell would act on, outside quotes
    } else {
      word += c, in_word = true;
    }
  }
  if (in_word) words.push_back(word);
  return words;
}

// Job lines (swath batch --emit-jobs, swath-fleet sweep, tune ask): the input's NUL-separated
// words, each quoted by shell_word() or refused in one sentence; a line of the quoted words must
// read back, word for word, as a POSIX shell reads it, and hold no control character.
void job_words(const std::string& text) {
  std::vector<std::string> words;
  for (std::size_t at = 0;;) {
    const std::size_t nul = text.find('\0', at);
    words.push_back(text.substr(at, nul == std::string::npos ? std::string::npos : nul - at));
    if (nul == std::string::npos) break;
    at = nul + 1;
  }
  std::string line;
  try {
    for (const std::string& w : words) line += (line.empty() ? "" : " ") + apps::shell_word(w);
  } catch (const base::InputError&) {
    return;
  }
  for (const char c : line)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) std::abort();
  if (shell_words_of(line) != words) std::abort();
}

// MAVLink bytes from a link: the frames must not depend on how the bytes are split, every byte is
// counted once, and each frame re-encodes to the bytes it came from and describes itself.
// Every number in a JSON value finite (ArduPilot reads them as doubles; "nan" is not JSON).
bool all_finite(const nlohmann::json& j) {
  if (j.is_number()) return std::isfinite(j.get<double>());
  if (j.is_array() || j.is_object())
    for (const auto& v : j)
      if (!all_finite(v)) return false;
  return true;
}

// Datagrams as swath-control ardupilot-json gets them over UDP (docs/swath-control.md): each a
// length byte and that many bytes, handled in turn by one server. Every answer is one JSON line
// as SIM_JSON.cpp reads it ("\n" first and last, an object of finite numbers); a datagram that
// is not a servo packet gets none and is counted.
void ardupilot_packets(const std::string& text) {
  static const control::ArduPilotJsonSettings settings;
  control::ArduPilotJsonServer server(settings);
  long long answered = 0, refused = 0;
  for (std::size_t at = 0; at < text.size() && answered + refused < 64;) {
    const std::size_t size =
        std::min<std::size_t>(static_cast<unsigned char>(text[at]), text.size() - at - 1);
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(text.data() + at + 1);
    at += size + 1;
    const std::optional<std::string> reply = server.handle(bytes, size);
    if (!reply) {
      ++refused;
      continue;
    }
    ++answered;
    if (reply->size() < 2 || reply->front() != '\n' || reply->back() != '\n') std::abort();
    const std::string line = reply->substr(1, reply->size() - 2);
    if (line.find('\n') != std::string::npos) std::abort();
    const nlohmann::json j = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
    if (!j.is_object() || !all_finite(j)) std::abort();
  }
  if (server.bad_packets() != refused) std::abort();
}

void mavlink_frames(const std::string& text) {
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(text.data());
  mavlink::FrameParser whole, pieces;
  whole.feed({bytes, text.size()});
  whole.finish();
  std::vector<std::vector<std::uint8_t>> a, b;
  for (mavlink::Frame f; whole.next(f);) {
    a.push_back(mavlink::serialize(f));
    mavlink::describe(f);
  }
  std::size_t at = 0, step = 1;
  while (at < text.size()) {  // piece lengths 1, 2, 3, ... 17, 1, ...
    const std::size_t n = std::min(step, text.size() - at);
    pieces.feed({bytes + at, n});
    at += n;
    step = step % 17 + 1;
    for (mavlink::Frame f; pieces.next(f);) b.push_back(mavlink::serialize(f));
  }
  pieces.finish();
  for (mavlink::Frame f; pieces.next(f);) b.push_back(mavlink::serialize(f));
  const mavlink::ParserStats& s = whole.stats();
  if (a != b ||
      s.bytes_in_frames + s.bytes_skipped + s.bytes_unknown + s.bytes_signed != text.size() ||
      whole.pending_bytes() != 0)
    std::abort();
  for (const auto& frame_bytes : a) {  // re-encoded frames are found again, alone
    mavlink::FrameParser again;
    again.feed(frame_bytes);
    mavlink::Frame f;
    if (!again.next(f) || mavlink::serialize(f) != frame_bytes) std::abort();
  }
}

// Runs `read`; bad input (InputError) is the expected way out.
template <typename F>
void expect_input_error_only(F read) {
  try {
    read();
  } catch (const base::InputError&) {
  }
}

// An area the reader accepts is classified too, as `swath classify` does.
void field(const std::string& text, geometry::FieldFormat format, const char* name) {
  expect_input_error_only([&] {
    const geometry::Field f = geometry::parse_field(text, format, name);
    geometry::describe_area(f.polygon);
  });
}

void mission_config(const std::string& text) {
  CLI::App app;
  apps::PlanCommand command;
  command.setup(app);
  expect_input_error_only([&] { apps::apply_mission_config(app, text, "fuzz.yaml"); });
}

// The same tree bit for bit: types, integers, the bits of every double (-0 is not 0), strings,
// and members in order.
bool same_bits(const nlohmann::json& a, const nlohmann::json& b) {
  if (a.type() != b.type()) return false;
  if (a.is_number_float())
    return std::bit_cast<std::uint64_t>(a.get<double>()) ==
           std::bit_cast<std::uint64_t>(b.get<double>());
  if (a.is_array() || a.is_object()) {
    if (a.size() != b.size()) return false;
    for (auto i = a.begin(), j = b.begin(); i != a.end(); ++i, ++j)
      if ((a.is_object() && i.key() != j.key()) || !same_bits(*i, *j)) return false;
    return true;
  }
  return a == b;
}

// A JSON document (every area, mission and summary file swath reads): the plain documents'
// own reader gives what nlohmann's alone gives, the same tree or the same refusal, word for word.
void json_document(const std::string& text) {
  std::optional<nlohmann::json> own, theirs;
  std::string own_error, their_error;
  try {
    own = base::parse_json_document(text, "fuzz.json");
  } catch (const base::InputError& e) {
    own_error = e.what();
  }
  try {
    theirs = base::detail::parse_json_document_nlohmann(text, "fuzz.json");
  } catch (const base::InputError& e) {
    their_error = e.what();
  }
  if (own_error != their_error || own.has_value() != theirs.has_value()) std::abort();
  if (own && !same_bits(*own, *theirs)) std::abort();
}

void plan_features(const std::string& text) {
  expect_input_error_only([&] {
    const planning::PlanFeatures f = planning::parse_mission_geojson(text, "mission.geojson");
    apps::coverage_image(f, planning::PlanFigures{}, 640, 480);
  });
}

// The drawing module on any scene: bytes become a small view (at most 48 x 48 px) and a few
// shapes, sizes and colours, each number either from the bytes or one of the hostile values
// (NaN, infinities, 0, 1e300, 1e9, ...). Drawing may only end in RenderError; what it draws is
// drawn again the same, and survives a PNG round trip.
class SceneBytes {
 public:
  explicit SceneBytes(const std::string& bytes) : bytes_(bytes) {}
  bool done() const { return at_ >= bytes_.size(); }
  unsigned byte() { return done() ? 0 : static_cast<unsigned char>(bytes_[at_++]); }
  int count(int most) { return static_cast<int>(byte() % (most + 1)); }
  double number() {
    static constexpr double kHostile[] = {std::numeric_limits<double>::quiet_NaN(),
                                          std::numeric_limits<double>::infinity(),
                                          -std::numeric_limits<double>::infinity(),
                                          0.0,
                                          1e300,
                                          -1e300,
                                          1e9,
                                          -1e9,
                                          1e-6,
                                          1.5e308,
                                          -1.5e308};
    const unsigned b = byte();
    if (b < std::size(kHostile)) return kHostile[b];
    return (static_cast<double>(b) + byte() / 256.0) / 4 - 10;  // -10 to 54: in or near the view
  }
  geometry::Point2 point() { return {number(), number()}; }
  render::Color color() {
    const auto channel = [&] {
      return static_cast<float>(byte() % 8 == 7 ? number() : byte() / 255.0);
    };
    return {channel(), channel(), channel(), channel()};
  }
  std::vector<geometry::Point2> points(int most) {
    std::vector<geometry::Point2> out(count(most));
    for (auto& p : out) p = point();
    return out;
  }

 private:
  const std::string& bytes_;
  std::size_t at_ = 0;
};

void render_scene(const std::string& bytes) {
  SceneBytes in(bytes);
  render::View view;
  view.width_px = in.count(48);
  view.height_px = in.count(48);
  view.px_per_m = in.number();
  view.origin_x_m = in.number();
  view.origin_y_m = in.number();
  render::Scene scene;
  scene.background = in.color();
  for (int i = in.count(4); i > 0; --i) {
    render::FilledPolygon p;
    for (int r = in.count(3); r > 0; --r) p.rings.push_back(in.points(24));
    p.fill = in.color();
    p.outline = in.color();
    p.outline_px = in.number();
    (in.byte() % 2 ? scene.screen_polygons : scene.polygons).push_back(std::move(p));
  }
  for (int i = in.count(4); i > 0; --i)
    scene.strips.push_back({in.point(), in.point(), in.number(), in.color()});
  for (int i = in.count(4); i > 0; --i) {
    render::Polyline l{in.points(32), in.number(), in.color(), in.number()};
    (in.byte() % 2 ? scene.screen_polylines : scene.polylines).push_back(std::move(l));
  }
  for (int i = in.count(4); i > 0; --i)
    scene.markers.push_back(
        {in.point(), in.number(), in.color(), static_cast<render::MarkerShape>(in.byte() % 3)});
  for (int i = in.count(3); i > 0; --i) {
    render::Label label;
    label.x_px = static_cast<int>(in.byte()) - 100;
    label.y_px = static_cast<int>(in.byte()) - 100;
    label.text = bytes.substr(0, in.count(40));
    label.height_px = in.number();
    label.color = in.color();
    scene.labels.push_back(std::move(label));
  }
  try {
    const render::Image image = render::draw(scene, view);
    if (image.width != view.width_px || image.height != view.height_px ||
        image.rgb.size() != 3u * image.width * image.height)
      std::abort();
    if (render::draw(scene, view).rgb != image.rgb) std::abort();  // same scene, same pixels
    if (render::decode_png(render::encode_png(image)).rgb != image.rgb) std::abort();
  } catch (const render::RenderError&) {
  }
}

// The folder the DEM targets write their input to (made once, private to the process): the DEM
// reader opens files by path, as `swath plan --terrain` does. It holds hill.asc, which the VRT
// seed reads (a VRT may read files in its own folder only).
const std::string& dem_folder() {
  static const std::string dir = [] {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "swath-fuzz-dem-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) std::abort();
    std::ofstream(pattern + "/hill.asc")
        << "ncols 4\nnrows 3\nxllcorner 8.53\nyllcorner 47.39\ncellsize 0.005\n"
           "400 402 404 406\n401 403 405 407\n402 404 406 408\n";
    return pattern;
  }();
  return dir;
}

// A DEM (swath plan --terrain): the bytes written to a file named `name`, opened and sampled
// on a grid over the seeds' area and at a few points elsewhere. Every height it gives is no height
// (NaN) or one on Earth (-430 to 8,850 m): anything else would be flown.
void dem(const std::string& bytes, const char* name) {
  const std::string path = dem_folder() + "/" + name;
  geometry::forget_dem(path);  // the previous input under this name
  { std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes; }
  std::vector<geometry::GeoPoint> points{{0, 0, 0}, {-89.9, 179.9, 0}, {47.39, 8.53, 0}};
  for (int i = 0; i <= 8; ++i)
    for (int j = 0; j <= 8; ++j) points.push_back({47.385 + 0.0025 * i, 8.525 + 0.0035 * j, 0});
  expect_input_error_only([&] {
    const auto ground = geometry::dem_ground(path);
    if (!(ground->resolution_m() > 0)) std::abort();
    for (const double h : ground->heights_m(points))
      if (!std::isnan(h) && !(h >= -430.0 && h <= 8'850.0)) std::abort();
  });
  geometry::forget_dem(path);
}

}  // namespace

namespace {

// The area, camera, fleet, mission and stage-plan readers of swath and swath-energy.
std::vector<Target> planning_and_energy_targets() {
  return {
      {"geojson",
       [](const std::string& t) { field(t, geometry::FieldFormat::geojson, "fuzz.geojson"); },
       {"share/fields/meadow.geojson", "share/fields/bowtie.geojson",
        "share/zones/meadow-pond.geojson"}},
      {"kml",
       [](const std::string& t) { field(t, geometry::FieldFormat::kml, "fuzz.kml"); },
       {"share/fields/vineyard.kml"}},
      {"csv",
       [](const std::string& t) { field(t, geometry::FieldFormat::csv, "fuzz.csv"); },
       {"share/fields/orchard.csv", "share/fields/yard-local.csv"}},
      {"camera",
       [](const std::string& t) {
         expect_input_error_only([&] { planning::parse_camera(t, "fuzz.yaml"); });
       },
       {"share/cameras/dji-phantom-4-pro.yaml", "share/cameras/dji-mavic-3e.yaml"}},
      {"fleet",
       [](const std::string& t) {
         expect_input_error_only([&] { vehicle::parse_fleet(t, "fuzz.yaml"); });
       },
       {"share/fleets/three-quads.yaml", "share/fleets/vineyard-pair.yaml",
        "share/fleets/short-range.yaml"}},
      {"mission_config", mission_config, {"tests/bad-input/seeds/mission.yaml"}},
      {"stage_plan",
       [](const std::string& t) {
         expect_input_error_only([&] { energy::parse_plan(t, "fuzz.stages"); });
       },
       {"plans/survey.stages"}},
      {"stage_plan_yaml",
       [](const std::string& t) {
         expect_input_error_only([&] { energy::parse_plan_yaml(t, "fuzz.yaml"); });
       },
       {"plans/survey.yaml"}},
      {"sim_config",
       [](const std::string& t) {
         expect_input_error_only([&] { energy::parse_sim_config(t, "fuzz.yaml"); });
       },
       {"plans/survey-sim.yaml", "plans/meadow-sim.yaml"}},
      {"drone_profile",
       [](const std::string& t) {
         expect_input_error_only([&] { energy::parse_drone_profile(t, "fuzz.yaml"); });
       },
       {"share/drones/quad-5ah.yaml"}},
      {"waypoint_mission",
       [](const std::string& t) {
         expect_input_error_only([&] { energy::parse_waypoint_missions(t, "fuzz.plan"); });
       },
       {"tests/bad-input/seeds/drone-1.plan", "tests/bad-input/seeds/mission.geojson"}},
      {"vehicle",
       [](const std::string& t) {
         expect_input_error_only([&] { vehicle::parse_vehicle(t, "fuzz.yaml"); });
       },
       {"share/vehicles/quad-f450.yaml", "share/vehicles/y6.yaml"}},
      {"environment",
       [](const std::string& t) {
         expect_input_error_only([&] { vehicle::parse_environment(t, "fuzz.yaml"); });
       },
       {"share/environments/arch.yaml", "share/environments/lab.yaml"}},
      {"power_trace",
       [](const std::string& t) {
         expect_input_error_only([&] { energy::parse_power_trace(t, "fuzz.csv"); });
       },
       {"tests/bad-input/seeds/power.csv"}},
      // swath render DIR: mission.geojson read back and drawn into a scene (no pixels).
      {"plan_features", plan_features, {"tests/bad-input/seeds/mission.geojson"}},
      {"render_scene", render_scene, {"tests/fuzz-regressions/render_scene/hostile-lines"}},
      {"json_document",
       json_document,
       {"tests/bad-input/seeds/summary.json", "tests/bad-input/seeds/drone-1.plan",
        "tests/bad-input/seeds/mission.geojson", "share/fields/meadow.geojson"}},
      {"plan_figures",
       [](const std::string& t) {
         expect_input_error_only([&] { planning::parse_plan_figures(t, "summary.json"); });
       },
       {"tests/bad-input/seeds/summary.json"}},
  };
}

// swath-control's inputs, MAVLink from a link, and GIS areas.
std::vector<Target> control_and_link_targets() {
  return {
      // swath-control: the control sections of a vehicle file, and a scheduler file.
      {"vehicle_control",
       [](const std::string& t) {
         expect_input_error_only([&] { control::parse_vehicle_control(t, "fuzz.yaml"); });
       },
       {"tests/bad-input/seeds/vehicle-control.yaml"}},
      {"scheduler",
       [](const std::string& t) {
         expect_input_error_only([&] { control::parse_scheduler_config(t, "fuzz.yaml"); });
       },
       {"share/schedulers/tt-400.yaml", "tests/bad-input/seeds/scheduler-reactive.yaml"}},
      // swath-control run's other inputs: the first line a `--set KEY=VALUE` (also read as a
      // random:N@WxH mission), the rest a YAML file it applies to; then the scheduler reader and
      // the vehicle file's battery section read the result.
      {"control_inputs",
       [](const std::string& t) {
         const std::size_t eol = std::min(t.find('\n'), t.size());
         const std::string first = t.substr(0, eol), rest = t.substr(std::min(eol + 1, t.size()));
         expect_input_error_only([&] { control::parse_random_spec(first); });
         const std::size_t eq = first.find('=');
         const control::Override o{first.substr(0, eq),
                                   eq == std::string::npos ? "" : first.substr(eq + 1)};
         expect_input_error_only([&] {
           const std::string text = control::apply_overrides(rest, "fuzz.yaml", {o});
           control::parse_scheduler_config(text, "fuzz.yaml");
         });
         expect_input_error_only([&] { energy::parse_battery_section(rest, "fuzz.yaml"); });
       },
       {"tests/bad-input/seeds/control-override.txt"}},
      // swath-control fit: trigger data (x, changed) and the fit of every method.
      {"trigger_data",
       [](const std::string& t) {
         expect_input_error_only([&] {
           const auto data = control::parse_trigger_data(t, "fuzz.csv");
           for (auto method : {control::FitMethod::logit_ols, control::FitMethod::logit_wls,
                               control::FitMethod::mle})
             control::trigger_threshold(control::fit_logistic(data, method), 0.6);
         });
       },
       {"tests/bad-input/seeds/trigger-data.csv"}},
      // MAVLink from a link (docs/swath-fleet.md): the frame parser and every message's decoder.
      // ArduPilot's servo packets to the JSON physics server (docs/swath-control.md).
      {"ardupilot_packets",
       [](const std::string& t) { ardupilot_packets(t); },
       {"tests/bad-input/seeds/ardupilot-servo.bin"}},
      {"mavlink_frames",
       [](const std::string& t) { mavlink_frames(t); },
       {"tests/bad-input/seeds/mavlink-frames.bin"}},
      // Job lines for a shell, GNU parallel or Slurm (docs/swath-plan.md, docs/swath-fleet.md).
      {"job_words",
       [](const std::string& t) { job_words(t); },
       {"tests/bad-input/seeds/job-words.bin"}},
      // GIS areas: WKT through OGR's parser, then swath's checks (docs/swath-plan.md).
      {"ogr_wkt",
       [](const std::string& t) { field(t, geometry::FieldFormat::wkt, "fuzz.wkt"); },
       {"tests/bad-input/seeds/field.wkt"}},
      // DEMs for terrain following (docs/swath-plan.md): GeoTIFF, ESRI ASCII grid, VRT.
      {"dem_geotiff",
       [](const std::string& t) { dem(t, "fuzz.tif"); },
       {"tests/bad-input/seeds/dem-hill.tif", "tests/bad-input/dem/truncated.tif"}},
      {"dem_ascii",
       [](const std::string& t) { dem(t, "fuzz.asc"); },
       {"tests/bad-input/dem/hill.asc", "tests/bad-input/dem/truncated.asc",
        "tests/bad-input/dem/spike.asc"}},
      {"dem_vrt",
       [](const std::string& t) { dem(t, "fuzz.vrt"); },
       {"tests/bad-input/seeds/dem-hill.vrt"}},
  };
}

// swath-fleet's world, fleet, fault, task-graph and event files.
std::vector<Target> fleet_targets() {
  return {
      // swath-fleet: world files (every kind) and the fleet file's simulated drones.
      {"world",
       [](const std::string& t) {
         expect_input_error_only([&] { worlds::parse_world(t, "fuzz.yaml"); });
       },
       {"share/worlds/hotspot.yaml", "share/worlds/road.yaml", "share/worlds/rf_field.yaml",
        "share/worlds/sites.yaml", "share/worlds/tracking.yaml", "share/worlds/static.yaml"}},
      {"fleet_file",
       [](const std::string& t) {
         expect_input_error_only([&] {
           fleet::parse_fleet_file(t, "fuzz.yaml", {42.3601, -71.0942, 0});
         });
       },
       {"share/fleets/tracking-pair.yaml", "share/fleets/three-quads.yaml",
        "share/weights/default.yaml", "tests/bad-input/seeds/fleet-mavlink.yaml"}},
      {"faults",
       [](const std::string& t) {
         expect_input_error_only([&] { fleet::parse_faults(t, "fuzz.yaml", {"a", "b"}, 3600); });
       },
       {"tests/bad-input/seeds/faults-list.yaml", "tests/bad-input/seeds/faults-random.yaml"}},
      // A run's task graph read back (history for the forecasters): refused in one sentence,
      // or forecast from and scored whatever its shape (cycles, dangling waiters, no places).
      {"dtg",
       [](const std::string& t) {
         expect_input_error_only([&] {
           const fleet::Dtg g = fleet::parse_dtg(t, "fuzz.json");
           auto gmf = fleet::gmf_forecaster({g});
           fleet::score_forecasts(*gmf, g);
           auto cv = fleet::constant_velocity_forecaster();
           fleet::score_forecasts(*cv, g.as_of(1.0));
           fleet::make_trace_app(g);  // trace replay's checks of the scripts
         });
       },
       {"tests/bad-input/seeds/dtg.json", "tests/bad-input/seeds/dtg-script.json"}},
      // The checker judges any text and never throws; the replay (render) refuses it in one
      // sentence or reads it.
      // The fleet file's GeoJSON fence (Polygon/MultiPolygon, Feature, FeatureCollection).
      {"fence_geojson",
       [](const std::string& t) {
         expect_input_error_only([&] { vehicle::parse_fence_geojson(t, "fuzz.geojson"); });
       },
       {"tests/bad-input/seeds/fence.geojson"}},
      {"fleet_events",
       [](const std::string& t) {
         fleet::check_events(t);
         expect_input_error_only([&] { fleet::replay_record(t, "fuzz.jsonl"); });
       },
       {"tests/bad-input/seeds/fleet-events.jsonl"}},
  };
}

}  // namespace

const std::vector<Target>& targets() {
  static const std::vector<Target> all = [] {
    std::vector<Target> out = planning_and_energy_targets();
    for (auto group : {control_and_link_targets, fleet_targets})
      for (Target& t : group()) out.push_back(std::move(t));
    return out;
  }();
  return all;
}

const Target* find_target(const std::string& name) {
  for (const Target& t : targets())
    if (name == t.name) return &t;
  return nullptr;
}

}  // namespace swath::fuzz
