#include "plan_command.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>

#include "basemap.hpp"
#include "coverage_image.hpp"
#include "data_dir.hpp"
#include "energy_plan_files.hpp"
#include "input_text.hpp"
#include "mission_config.hpp"
#include "plan_html.hpp"
#include "progress_bar.hpp"
#include "swath/base/file_text.hpp"
#include "swath/base/freed_memory.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/output_set.hpp"
#include "swath/geometry/geotiff.hpp"
#include "swath/geometry/ground.hpp"
#include "swath/missions/writers.hpp"
#include "swath/planning/coverage_grid.hpp"
#include "swath/planning/limits.hpp"
#include "swath/planning/plan_features.hpp"
#include "swath/planning/survey.hpp"
#include "swath/planning/survey_files.hpp"
#include "verify_inputs.hpp"

namespace swath::apps {
namespace {

using base::fixed_text;
using base::round_to;

using base::InputError;

// "LAT,LON" in degrees.
geometry::GeoPoint parse_lat_lon(const std::string& text, const std::string& option) {
  const auto pair = parse_number_pair(text, ',');
  if (!pair)
    throw InputError(option + " '" + text + "': expected LAT,LON in degrees, e.g. 47.397,8.541");
  const auto [lat, lon] = *pair;
  if (std::abs(lat) > 90 || std::abs(lon) > 180)
    throw InputError(option + " '" + text +
                     "': latitude must be within ±90 and longitude within ±180 degrees");
  return {lat, lon, 0.0};
}

std::pair<double, double> parse_pattern(const std::string& text) {
  const auto pair = parse_number_pair(text, 'x');
  if (!pair) throw InputError("--pattern '" + text + "': expected WxH in metres, e.g. 1.5x1.5");
  return *pair;
}

template <typename E>
E lookup(const std::map<std::string, E>& table, const std::string& value) {
  return table.at(value);  // CLI11 has already checked membership
}

// coverage.tif: the coverage grid as a GeoTIFF of the plan's local frame.
std::string coverage_tif(const planning::SurveyPlan& plan, double cell_m) {
  const planning::CoverageGrid g = planning::coverage_grid(plan, cell_m);
  geometry::LocalRaster r;
  r.origin = plan.request.field.frame->origin();
  r.west_m = g.west_m;
  r.north_m = g.north_m;
  r.cell_m = g.cell_m;
  r.width = g.width;
  r.height = g.height;
  r.bands.emplace_back("photos", g.photos);
  r.bands.emplace_back("area", std::vector<std::uint16_t>(g.inside.begin(), g.inside.end()));
  return geometry::geotiff_bytes(r);
}

std::string kilometres(double m) {
  return fixed_text(m / 1000, 2) + " km";
}

}  // namespace

void PlanCommand::setup(CLI::App& app) {
  app_ = &app;
  add_input_options(app);
  add_imaging_options(app);
  add_sweep_options(app);
  add_division_options(app);
  add_output_options(app);
  add_mission_file_options(app);
  add_terrain_energy_options(app);
}

// The area, the camera, the output directory, a mission config.
void PlanCommand::add_input_options(CLI::App& app) {
  app.add_option("--config", config_,
                 "Mission YAML holding any of these options (keys = long option names, "
                 "'field' for FIELD); command-line flags override it")
      ->check(CLI::ExistingFile);
  app.add_option("FIELD", field_,
                 "Area file: .geojson/.json, .kml or .csv (lon,lat), or any GIS file GDAL reads "
                 "(.shp, .zip, .gpkg, .kmz, .gpx, .fgb, .gml, .wkt; projected ones reprojected)");
  app.add_option("--camera", camera_,
                 "Camera: an id or name from 'swath cameras', or a camera YAML file");
  app.add_option("-o,--output", output_,
                 "Directory to write the mission files into (created if missing)");
}

// How the camera images: altitude or GSD and overlaps, or detection.
void PlanCommand::add_imaging_options(CLI::App& app) {
  app.add_option("--mode", mode_,
                 "photogrammetry (altitude or GSD and overlaps) or detection (paper 001: pattern "
                 "size and pixels)")
      ->check(CLI::IsMember({"photogrammetry", "detection"}))
      ->capture_default_str();
  app.add_option("--altitude", altitude_m_,
                 "Photogrammetry: flight altitude above home, metres (above the ground with "
                 "--terrain)");
  app.add_option("--gsd", gsd_cm_,
                 "Photogrammetry: ground sample distance, cm per pixel (sets the altitude)");
  app.add_option("--side-overlap", side_overlap_,
                 "Photogrammetry: overlap of adjacent lines, fraction in [0, 1)")
      ->capture_default_str();
  app.add_option("--front-overlap", front_overlap_,
                 "Photogrammetry: overlap of successive photos, fraction in [0, 1)")
      ->capture_default_str();
  app.add_option("--pattern", pattern_,
                 "Ground pattern WxH in metres to detect (detection mode; in photogrammetry "
                 "mode only checked: warns when the altitude is above h_max)");
  app.add_option("--min-pixels", min_pixels_,
                 "Pixels the pattern must span at least (with --pattern)");
  app.add_option("--overlap", overlap_,
                 "Detection: overlap v in [0, 1], altitude = h_max (1 + v) / 2")
      ->capture_default_str();
  app.add_flag("--portrait", portrait_,
               "Image height across the flight line (default: landscape, width across)");
}

// Lines: direction, placement, turns, start and home.
void PlanCommand::add_sweep_options(CLI::App& app) {
  app.add_option("--angle", angle_deg_,
                 "Fly lines at this compass bearing, degrees clockwise from north "
                 "(default: the exact minimum-height direction)");
  app.add_option("--angle-search", angle_search_,
                 "exact (rotating calipers) or scan (paper 001, --angle-step)")
      ->check(CLI::IsMember({"exact", "scan"}))
      ->capture_default_str();
  app.add_option("--angle-step", angle_step_deg_, "Step of --angle-search scan, degrees")
      ->capture_default_str();
  app.add_option("--line-placement", placement_,
                 "centered (fewest lines, centred) or paper (Algorithm 2)")
      ->check(CLI::IsMember({"centered", "paper"}))
      ->capture_default_str();
  app.add_option("--turnaround", turnaround_m_,
                 "Extend every line by this many metres at both ends (default 0; fixed-wing: one "
                 "turn radius, to roll out on the line)");
  app.add_option("--waypoint-spacing", waypoint_spacing_m_,
                 "Add waypoints along lines at most this many metres apart");
  app.add_option("--start", start_,
                 "Entry corner: nearest-home (shortest home legs), sw, se, nw or ne")
      ->check(CLI::IsMember({"nearest-home", "sw", "se", "nw", "ne"}))
      ->capture_default_str();
  app.add_option("--home", home_,
                 "Home (take-off and landing) LAT,LON in degrees (default: the survey's entry "
                 "point, entered from the south-west)");
  app.add_flag("--far-home", far_home_,
               "Plan with a home (--home, or the fleet's) farther than 50 km from the area "
               "(refused otherwise: usually latitude and longitude swapped)");
  app.add_flag("--local", local_, "The CSV area is x,y in metres (needs --origin)");
  area_choice_.add_options(app);
  app.add_option("--origin", origin_,
                 "LAT,LON of the local frame's origin (0, 0) for a --local area");
  app.add_option(
         "--concave", concave_,
         "Non-convex area (reflex vertices or holes): split (cells swept without leaving the "
         "area, transits routed around holes), hull (paper 001: its convex hull; the summary "
         "reports the swath outside) or reject")
      ->check(CLI::IsMember({"split", "hull", "reject"}))
      ->capture_default_str();
  app.add_option("--split-cells", split_cells_,
                 "How split cuts the area: runs (lanes laid first, cut where they meet the "
                 "boundary, chained into zigzags), boustrophedon (cells of the polygon, the first "
                 "method) or best (both, per direction; the shorter path wins)")
      ->check(CLI::IsMember({"runs", "boustrophedon", "best"}))
      ->capture_default_str();
  app.add_option("--directions", directions_,
                 "Split line directions: one for the whole area, or per-region (each region of "
                 "an L or a strip with a wide head at its own direction, where the whole path is "
                 "shorter and coverage holds; one drone or path division, no --crosshatch)")
      ->check(CLI::IsMember({"one", "per-region"}))
      ->capture_default_str();
  app.add_option("--threads", threads_,
                 "Threads for the split's direction search (0: every hardware thread); the files "
                 "do not depend on it")
      ->check(CLI::Range(0, 256))
      ->capture_default_str();
}

// Several drones: division and balance.
void PlanCommand::add_division_options(CLI::App& app) {
  app.add_option("--drones", drones_, "Divide the survey among N equal drones sharing the home");
  app.add_option("--fleet", fleet_,
                 "Fleet YAML: home, and per drone a capability or battery_level, endurance_s and "
                 "speed_m_s (optional own home); divides the survey among them");
  app.add_option("--division", division_,
                 "With a fleet: path (cut the one sweep path, paper Alg. 3) or region "
                 "(bands along the lanes, paper Alg. 4)")
      ->check(CLI::IsMember({"path", "region"}))
      ->capture_default_str();
  app.add_option("--balance", balance_,
                 "With a fleet: capability (shares in proportion to the corrected "
                 "capabilities, the paper) or makespan (shortest longest flight)")
      ->check(CLI::IsMember({"capability", "makespan"}))
      ->capture_default_str();
  app.add_flag("--allow-partial", allow_partial_,
               "Plan what a fleet short of range can fly (the summary says what stays unflown) "
               "instead of refusing");
}

// Pictures, the coverage raster, repair.
void PlanCommand::add_output_options(CLI::App& app) {
  app.add_flag("--render", render_,
               "Also draw coverage.png: the area, camera footprints, paths, home, scale bar");
  app.add_option("--size", size_, "Size of coverage.png, WxH pixels")->capture_default_str();
  app.add_flag("--progress", progress_,
               "Show the split's direction search as a progress bar (only on a terminal)");
  app.add_flag("--html", html_,
               "Also write plan.html: the plan on a map, one self-contained page (layers, "
               "waypoint details, summary); it fetches nothing unless --basemap-url is given");
  app.add_option("--basemap-url", basemap_url_,
                 "plan.html: XYZ tile template drawn behind the plan "
                 "(http(s)://host/{z}/{x}/{y}.png; the page then fetches these tiles)");
  app.add_option("--basemap", basemap_,
                 "coverage.png and plan.html: a raster drawn behind the plan (an orthophoto: "
                 "GeoTIFF or any raster GDAL reads, any CRS; reprojected, read from disk only)");
  app.add_flag("--coverage-tif", coverage_tif_,
               "Also write coverage.tif, a GeoTIFF in the plan's local frame (PROJ ortho about "
               "its origin): band 1 the planned photos over each cell, band 2 1 inside the area");
  app.add_option("--coverage-cell", coverage_cell_m_,
                 "coverage.tif's cell size, metres (enlarged to keep it under 16 million cells)")
      ->capture_default_str();
  app.add_flag("--repair", repair_,
               "An outer ring that crosses itself: plan the areas it encloses (union of its faces) "
               "instead of refusing it; the summary and a warning say what was done");
  app.add_option(
      "--exclude", exclude_,
      "No-fly zones: an area file (.geojson, .kml, .csv lon,lat); every polygon of it (each "
      "feature, each part of a MultiPolygon) is a zone; repeat for more. Honoured by split");
}

// What the mission files hold and which formats besides the defaults.
void PlanCommand::add_mission_file_options(CLI::App& app) {
  app.add_option("--firmware", firmware_, "ardupilot or px4 (QGC firmwareType)")
      ->check(CLI::IsMember({"ardupilot", "px4"}))
      ->capture_default_str();
  app.add_option("--vehicle", vehicle_, "multirotor or fixedwing (QGC vehicleType)")
      ->check(CLI::IsMember({"multirotor", "fixedwing"}))
      ->capture_default_str();
  app.add_option("--speed", speed_m_s_, "Cruise speed, m/s (default 5 multirotor, 15 fixed wing)");
  app.add_option("--clearance", clearance_m_,
                 "Keep every waypoint and leg (lines, turns, transits, legs to and from home) this "
                 "many metres from holes and no-fly zones; the summary reports what is kept")
      ->capture_default_str();
  app.add_option("--ceiling", ceiling_m_,
                 "The highest a mission may fly, metres above the ground (with --terrain) or above "
                 "home (default 120, the common legal limit): altitude layers stay under it (a "
                 "fleet needing more is refused), and files that fly higher are refused as "
                 "written (see swath verify)")
      ->capture_default_str();
  app.add_option("--boundary-clearance", boundary_clearance_m_,
                 "Keep lines and turns this many metres inside the outer boundary")
      ->capture_default_str();
  app.add_option("--outside-margin", outside_margin_m_,
                 "Split: a line may cross up to this many metres outside the outer boundary "
                 "(never into a no-fly zone or its clearance) to join its pieces into one line, "
                 "e.g. along a ragged edge; its ends stay inside. The summary reports the line "
                 "length outside")
      ->capture_default_str();
  app.add_option("--trigger", trigger_,
                 "Camera: distance (every trigger distance, DO_SET_CAM_TRIGG_DIST), time (every "
                 "trigger distance / speed seconds, IMAGE_START_CAPTURE) or hover (stop and shoot "
                 "at each photo point); photos on the lines only")
      ->check(CLI::IsMember({"distance", "time", "hover"}))
      ->capture_default_str();
  app.add_option("--camera-command", camera_command_,
                 "Hover shots: digicam (DO_DIGICAM_CONTROL, relay/servo cameras) or "
                 "image-capture (IMAGE_START_CAPTURE, MAVLink cameras)")
      ->check(CLI::IsMember({"digicam", "image-capture"}))
      ->capture_default_str();
  app.add_flag("--photos-in-turns", photos_in_turns_,
               "Keep the camera on through turns that stay inside the area (default: started at "
               "each line, stopped before each turn)");
  app.add_option("--gimbal-pitch", gimbal_pitch_deg_,
                 "Camera pitch set once at the start, degrees (-90 nadir, 0 level)")
      ->capture_default_str();
  app.add_flag("--crosshatch", crosshatch_,
               "Fly the lines a second time at 90 degrees (for 3-D models)");
  app.add_option(
      "--fence-margin", fence_margin_m_,
      "The .plan's inclusion fence: the area grown by this many metres (default: "
      "turnaround + half the footprint width + 10 m, or for a multirotor turnaround + its "
      "stopping distance + 5 m where that is larger)");
  app.add_option("--layer-spacing", layer_spacing_m_,
                 "Drones of one plan whose paths come within 10 m of each other fly this many "
                 "metres apart in height (altitude layers above the imaging altitude)")
      ->capture_default_str();
  app.add_flag("--fence-files", fence_files_,
               "Also write fence.waypoints, fence.fen and rally.waypoints for Mission Planner");
  app.add_flag("--litchi", litchi_,
               "Also write each flight as a Litchi mission CSV (NAME-litchi.csv; above 99 "
               "waypoints NAME-litchi-1.csv, -2, ..., each starting where the last ended): "
               "heights above the take-off point, the speed, heading along each leg, the gimbal "
               "pitch, photos by distance or time on the lines; multirotors up to 15 m/s");
  app.add_flag("--dji", dji_,
               "Also write each flight as a DJI WPML KMZ for DJI Pilot 2 (NAME.kmz: "
               "wpmz/template.kml, wpmz/waylines.wpml): the same points, takePhoto every trigger "
               "distance from each line's start to its end, gimbal pitch, go-home or --land; the "
               "aircraft and payload from the camera's dji_* keys (warns without them)");
  app.add_flag("--qgc-survey", qgc_survey_,
               "Also write NAME-survey.plan: the flight as a QGroundControl Survey item, editable "
               "in QGC (area, angle, camera, overlaps, turnaround; QGC flies swath's lines until "
               "the survey is edited); one drone, a convex area without holes, zones or terrain");
}

// Terrain following, landing, sorties and energy plans.
void PlanCommand::add_terrain_energy_options(CLI::App& app) {
  app.add_option("--terrain", terrain_,
                 "Follow the ground of this DEM (any GDAL raster: GeoTIFF, .asc, .hgt, VRT; any "
                 "CRS; heights in metres unless it or --dem-units says otherwise): every waypoint "
                 "at the altitude above the ground under "
                 "it, waypoints added where the ground departs from a leg's straight line by more "
                 "than --terrain-tolerance; the DEM must cover the homes and the area");
  app.add_option("--terrain-tolerance", terrain_tolerance_m_,
                 "With --terrain: how far the height above ground may depart from --altitude "
                 "between waypoints, metres")
      ->capture_default_str();
  app.add_option("--altitude-frame", altitude_frame_,
                 "Altitudes in the .plan and .waypoints files: relative (above the take-off "
                 "point), amsl (above mean sea level, needs --terrain), terrain (MAV_FRAME_GLOBAL_"
                 "TERRAIN_ALT: the autopilot's terrain data, needs --terrain for the checks); "
                 "Litchi and DJI files are always relative to the take-off point")
      ->check(CLI::IsMember({"relative", "amsl", "terrain"}))
      ->capture_default_str();
  app.add_option("--dem-heights", dem_heights_,
                 "What the DEM's heights are measured from: geoid (mean sea level: SRTM, "
                 "Copernicus, national DEMs) or ellipsoid (WGS84; EGM96 is subtracted)")
      ->check(CLI::IsMember({"geoid", "ellipsoid"}))
      ->capture_default_str();
  app.add_option("--dem-units", dem_units_,
                 "The unit of the DEM's heights: m (default), ft (0.3048 m) or us-ft (US survey "
                 "foot, 1200/3937 m); a DEM that declares its unit is read in it, and a "
                 "--dem-units that contradicts it is refused")
      ->check(CLI::IsMember({"m", "ft", "us-ft"}));
  app.add_flag("--land", land_,
               "End with a landing at home (NAV_LAND) instead of return-to-launch");
  app.add_option("--max-bank", max_bank_deg_,
                 "Fixed-wing: bank limit, degrees; sets the minimum turn radius v^2 / (g tan bank)")
      ->capture_default_str();
  app.add_option("--sorties", sorties_,
                 "auto: cut each drone's flight into sorties, the first within the charge it "
                 "takes off with (the fleet's battery_level x endurance), the later ones a full "
                 "battery's endurance, less the reserve (NAME-1.plan, NAME-2.plan, ...); off: one "
                 "flight")
      ->check(CLI::IsMember({"auto", "off"}))
      ->capture_default_str();
  app.add_option("--endurance", endurance_s_,
                 "Flight time on a full battery, seconds, for drones the fleet gives none: "
                 "sorties, and without them a flight longer than the charge less the reserve is "
                 "refused");
  app.add_option("--reserve", reserve_,
                 "Share of the charge a flight takes off with kept in hand, for sorties and the "
                 "flight-time refusal (0: the whole charge may be flown)")
      ->capture_default_str();
  app.add_option("--energy-plan", energy_plan_,
                 "Also write the zigzag as a stage plan for 'swath-energy run' under this file "
                 "name in -o DIR (e.g. meadow.stages; with a fleet, NAME-<drone>.EXT each): lines, "
                 "half-circle turns, c1 scaling the line spacing");
  app.add_option("--energy-min-coverage", energy_min_coverage_,
                 "Energy plan: c1's bounds keep at least this fraction of the area covered")
      ->capture_default_str();
  app.add_option("--energy-computation", energy_computations_,
                 "Energy plan: LO,HI bounds of a computation parameter on lines and turns, one "
                 "per computation of the simulation config (default: 2,10 and 32,448 as in "
                 "plans/survey-sim.yaml); 'none' for none")
      ->capture_default_str();
}

void PlanCommand::check_numbers() const {
  using namespace planning::limits;
  if (altitude_m_) base::check_range(*altitude_m_, kAltitude_m, "--altitude");
  if (gsd_cm_) base::check_range(*gsd_cm_, kGsd_cm, "--gsd");
  check_overlap(side_overlap_, "--side-overlap");
  check_overlap(front_overlap_, "--front-overlap");
  base::check_range(overlap_, kDetectionOverlap, "--overlap");
  if (min_pixels_) base::check_range(*min_pixels_, kMinPixels, "--min-pixels");
  if (angle_deg_) base::check_range(*angle_deg_, kBearing_deg, "--angle");
  base::check_range(angle_step_deg_, kAngleStep_deg, "--angle-step");
  if (turnaround_m_) base::check_range(*turnaround_m_, kTurnaround_m, "--turnaround");
  base::check_range(clearance_m_, kClearance_m, "--clearance");
  base::check_range(boundary_clearance_m_, kClearance_m, "--boundary-clearance");
  base::check_range(outside_margin_m_, kClearance_m, "--outside-margin");
  base::check_range(gimbal_pitch_deg_, kGimbalPitch_deg, "--gimbal-pitch");
  if (fence_margin_m_) base::check_range(*fence_margin_m_, kFenceMargin_m, "--fence-margin");
  base::check_range(layer_spacing_m_, kLayerSpacing_m, "--layer-spacing");
  base::check_range(ceiling_m_, kCeiling_m, "--ceiling");
  base::check_range(max_bank_deg_, kBank_deg, "--max-bank");
  if (endurance_s_) base::check_range(*endurance_s_, kEndurance_s, "--endurance");
  base::check_range(reserve_, kReserve, "--reserve");
  if (waypoint_spacing_m_)
    base::check_range(*waypoint_spacing_m_, kWaypointSpacing_m, "--waypoint-spacing");
  if (drones_) base::check_range(*drones_, kDrones, "--drones");
  if (speed_m_s_) base::check_range(*speed_m_s_, kSpeed_m_s, "--speed");
  base::check_range(coverage_cell_m_, kCoverageCell_m, "--coverage-cell");
}

planning::SurveyRequest PlanCommand::request() const {
  planning::SurveyRequest request;
  geometry::FieldReadOptions read_options;
  read_options.local_metres = local_;
  area_choice_.apply(read_options);
  request.field = geometry::read_field(field_, read_options);
  if (local_) {
    if (origin_.empty())
      throw InputError(field_ + ": a --local area needs --origin LAT,LON to place it on the map");
    geometry::place_local_field(request.field, parse_lat_lon(origin_, "--origin"));
  } else if (!origin_.empty()) {
    throw InputError("--origin only applies to a --local area");
  }
  fill_request(request);
  return request;
}

void PlanCommand::check_options() {
  if (!config_.empty())
    apply_mission_config(
        *app_, base::read_text_file(config_, "mission config", base::kMaxConfigFileBytes), config_);
  if (camera_.empty()) throw InputError("no camera: give --camera (see 'swath cameras')");
  check_numbers();
  if (local_ && origin_.empty())
    throw InputError("a --local area needs --origin LAT,LON to place it on the map");
  if (!local_ && !origin_.empty()) throw InputError("--origin only applies to a --local area");
  if (local_) parse_lat_lon(origin_, "--origin");
  planning::SurveyRequest request;
  fill_request(request);
  check_file_options();
}

void PlanCommand::fill_request(planning::SurveyRequest& request) const {
  request.camera = planning::find_camera(camera_, share_dir() / "cameras");

  std::optional<planning::DetectionMode> pattern;
  if (!pattern_.empty() || min_pixels_) {
    if (pattern_.empty() || !min_pixels_)
      throw InputError("--pattern and --min-pixels go together");
    const auto [w, h] = parse_pattern(pattern_);
    pattern = planning::DetectionMode{w, h, *min_pixels_, overlap_};
  }
  if (mode_ == "detection") {
    if (!pattern) throw InputError("detection mode needs --pattern WxH and --min-pixels N");
    if (altitude_m_ || gsd_cm_)
      throw InputError("detection mode sets the altitude from the pattern; drop --altitude/--gsd");
    request.mode = *pattern;
  } else {
    if (!altitude_m_ && !gsd_cm_)
      throw InputError("photogrammetry mode needs --altitude M or --gsd CM");
    planning::PhotogrammetryMode m;
    m.altitude_m = altitude_m_;
    if (gsd_cm_) m.gsd_m = *gsd_cm_ / 100.0;
    m.side_overlap = side_overlap_;
    m.front_overlap = front_overlap_;
    request.mode = m;
    request.pattern = pattern;
  }
  request.orientation =
      portrait_ ? planning::ImageOrientation::portrait : planning::ImageOrientation::landscape;
  if (angle_deg_) {
    request.angle_search = planning::AngleSearch::fixed;
    request.line_bearing_deg = *angle_deg_;
  } else {
    request.angle_search =
        angle_search_ == "scan" ? planning::AngleSearch::scan : planning::AngleSearch::exact;
  }
  request.angle_step_deg = angle_step_deg_;
  request.placement =
      placement_ == "paper" ? planning::LinePlacement::paper : planning::LinePlacement::centered;
  request.turnaround_m = turnaround_m_;
  request.waypoint_spacing_m = waypoint_spacing_m_;
  request.start =
      lookup<planning::StartCorner>({{"nearest-home", planning::StartCorner::nearest_home},
                                     {"sw", planning::StartCorner::sw},
                                     {"se", planning::StartCorner::se},
                                     {"nw", planning::StartCorner::nw},
                                     {"ne", planning::StartCorner::ne}},
                                    start_);
  if (!home_.empty()) request.home = parse_lat_lon(home_, "--home");
  request.far_home = far_home_;
  request.repair = repair_;
  if (drones_ && !fleet_.empty()) throw InputError("give --drones or --fleet, not both");
  if (drones_) {
    const geometry::GeoPoint fleet_home = request.home ? *request.home : geometry::GeoPoint{};
    request.fleet = vehicle::equal_fleet(*drones_, fleet_home);
    if (!request.home)
      request.fleet->home = geometry::GeoPoint{std::nan(""), 0, 0};  // the plan's default home
  }
  if (!fleet_.empty()) {
    request.fleet = vehicle::parse_fleet(
        base::read_text_file(fleet_, "fleet file", base::kMaxConfigFileBytes), fleet_);
    request.fleet_name = fleet_;
    if (!request.home) request.home = request.fleet->home;
  }
  request.division =
      division_ == "region" ? planning::DivisionMode::region : planning::DivisionMode::path;
  request.balance =
      balance_ == "makespan" ? planning::Balance::makespan : planning::Balance::capability;
  request.allow_partial = allow_partial_;
  request.concave = concave_ == "reject" ? planning::ConcaveMode::reject
                    : concave_ == "hull" ? planning::ConcaveMode::hull
                                         : planning::ConcaveMode::split;
  request.split_cells = split_cells_ == "runs"            ? planning::SplitCells::runs
                        : split_cells_ == "boustrophedon" ? planning::SplitCells::boustrophedon
                                                          : planning::SplitCells::best;
  request.split_directions = directions_ == "per-region" ? planning::SplitDirections::per_region
                                                         : planning::SplitDirections::one;
  request.threads = threads_;
  // Every area of an --exclude file is a zone, read as swath verify reads them.
  for (const preflight::Zone& zone : zones_from_files(exclude_)) {
    request.exclusions.push_back(zone.ring);
    request.exclusion_names.push_back(zone.name);
  }
  request.firmware = firmware_ == "px4" ? planning::Firmware::px4 : planning::Firmware::ardupilot;
  request.vehicle =
      vehicle_ == "fixedwing" ? planning::Vehicle::fixedwing : planning::Vehicle::multirotor;
  request.speed_m_s = speed_m_s_;
  // DJI flies no slower than 1 m/s: every file of the plan approaches its stops beside no-fly
  // zones at that speed at least, and the stops are placed for its overrun.
  if (dji_) request.slowest_approach_m_s = missions::kDjiMinSpeed_m_s;
  request.clearance_m = clearance_m_;
  request.outside_margin_m = outside_margin_m_;
  request.boundary_clearance_m = boundary_clearance_m_;
  request.triggering.mode = trigger_ == "time"    ? planning::TriggerMode::time
                            : trigger_ == "hover" ? planning::TriggerMode::hover
                                                  : planning::TriggerMode::distance;
  request.triggering.command = camera_command_ == "image-capture"
                                   ? planning::CameraCommand::image_capture
                                   : planning::CameraCommand::digicam;
  request.triggering.photos_in_turns = photos_in_turns_;
  request.triggering.gimbal_pitch_deg = gimbal_pitch_deg_;
  request.crosshatch = crosshatch_;
  request.fence_margin_m = fence_margin_m_;
  request.layer_spacing_m = layer_spacing_m_;
  request.ceiling_m = ceiling_m_;
  request.land = land_;
  request.max_bank_deg = max_bank_deg_;
  request.sorties = sorties_ == "auto";
  request.endurance_s = endurance_s_;
  request.reserve = reserve_;
  request.terrain = terrain();
}

std::optional<planning::TerrainRequest> PlanCommand::terrain() const {
  if (terrain_.empty()) {
    if (altitude_frame_ != "relative")
      throw InputError("--altitude-frame " + altitude_frame_ +
                       " needs --terrain DEM (the ground's heights)");
    if (!dem_units_.empty())
      throw InputError("--dem-units needs --terrain DEM (the ground's heights)");
    if (app_ && app_->count("--dem-heights") > 0)
      throw InputError("--dem-heights needs --terrain DEM (the ground's heights)");
    return std::nullopt;
  }
  base::check_range(terrain_tolerance_m_, planning::limits::kTerrainTolerance_m,
                    "--terrain-tolerance");
  planning::TerrainRequest t;
  t.ground = geometry::dem_ground(
      terrain_,
      dem_heights_ == "ellipsoid" ? geometry::DemHeights::ellipsoid : geometry::DemHeights::geoid,
      geometry::dem_unit_m(dem_units_));
  t.tolerance_m = terrain_tolerance_m_;
  t.frame = altitude_frame_ == "amsl"      ? planning::AltitudeFrame::amsl
            : altitude_frame_ == "terrain" ? planning::AltitudeFrame::terrain
                                           : planning::AltitudeFrame::relative;
  return t;
}

void PlanCommand::check_file_options() const {
  if (!basemap_url_.empty() && !html_)
    throw InputError("--basemap-url draws behind plan.html: give --html too");
  if (!basemap_.empty() && !html_ && !render_)
    throw InputError("--basemap draws behind coverage.png or plan.html: give --render or --html");
}

std::vector<std::pair<std::string, std::string>> PlanCommand::files(
    const planning::SurveyPlan& plan) const {
  check_file_options();
  const planning::FileOptions options{fence_files_, litchi_, dji_, qgc_survey_};
  auto files = planning::survey_files(plan, options);
  export_warnings_ = planning::export_warnings(plan, options);
  if (!energy_plan_.empty()) {
    EnergyPlanRequest energy;
    energy.file_name = energy_plan_;
    energy.min_covered_fraction = energy_min_coverage_;
    energy.field = std::filesystem::path(field_).filename().string();
    for (const std::string& c : energy_computations_)
      if (c != "none") energy.computations.push_back(parse_interval(c, "--energy-computation"));
    for (auto& f : energy_plan_files(plan, energy, energy_warnings_)) {
      for (const auto& [name, content] : files)
        if (name == f.first)
          throw InputError("--energy-plan " + energy_plan_ +
                           ": the stage plan would be written as " + f.first +
                           ", a file of the mission set itself; choose another name");
      files.push_back(std::move(f));
    }
  }
  if (render_) {
    const auto [w, h] = parse_size(size_);
    CoverageImage image =
        coverage_image(planning::plan_features(plan), planning::plan_figures(plan), w, h);
    if (!basemap_.empty()) put_basemap_under(image, basemap_);
    files.push_back({"coverage.png", render::encode_png(render::draw(image.scene, image.view))});
  }
  if (coverage_tif_) files.push_back({"coverage.tif", coverage_tif(plan, coverage_cell_m_)});
  // summary.json lists the whole set (docs/swath-plan.md).
  std::vector<std::string> set_names;
  for (const auto& f : files) set_names.push_back(f.first);
  if (html_) set_names.push_back("plan.html");
  files[1].second = planning::summary_json(plan, set_names);
  // Last: the page holds the other files as written, summary.json included.
  if (html_) {
    const auto lookup = [&files](const std::string& name) -> std::optional<std::string> {
      for (const auto& [n, text] : files)
        if (n == name) return text;
      return std::nullopt;
    };
    files.push_back({"plan.html", plan_html(lookup, output_, basemap_url_, basemap_)});
  }
  return files;
}

void PlanCommand::report(const planning::SurveyPlan& plan,
                         const std::vector<std::pair<std::string, std::string>>& files) const {
  const planning::Imaging& im = plan.imaging;
  std::printf("swath plan: %s -> %s\n", field_.c_str(), output_.c_str());
  const std::string handling = plan.handling == planning::Handling::hull
                                   ? " (flown over its convex hull)"
                               : plan.handling == planning::Handling::split
                                   ? " (split into " + std::to_string(plan.cells.size()) + " cells)"
                                   : "";
  std::printf("  area       %s, %s ha%s\n",
              std::string(geometry::to_string(plan.facts.classification.type)).c_str(),
              fixed_text(*plan.facts.area_m2 / 1e4, 3).c_str(), handling.c_str());
  std::printf("  camera     %s, %s: altitude %s m, GSD %s cm/px, footprint %s x %s m\n",
              plan.request.camera.name.c_str(), mode_.c_str(), fixed_text(im.altitude_m, 1).c_str(),
              fixed_text(im.gsd_m * 100, 3).c_str(), fixed_text(im.footprint_across_m, 1).c_str(),
              fixed_text(im.footprint_along_m, 1).c_str());
  std::printf(
      "  lines      %zu at bearing %s deg, %s m apart, photo every %s m\n", plan.sweep.lines.size(),
      fixed_text(geometry::line_bearing_deg(plan.sweep.angle_deg), 2).c_str(),
      fixed_text(im.line_spacing_m, 2).c_str(), fixed_text(im.trigger_distance_m, 2).c_str());
  if (!plan.region_angles_deg.empty()) {
    std::string regions;
    for (double a : plan.region_angles_deg) {
      if (!regions.empty()) regions += ", ";
      regions += fixed_text(geometry::line_bearing_deg(a), 2);
    }
    std::printf("  regions    %zu, lines at bearings %s deg\n", plan.region_angles_deg.size(),
                regions.c_str());
  }
  if (plan.terrain) {
    const planning::TerrainFacts& t = *plan.terrain;
    std::printf(
        "  terrain    ground %s to %s m, %s m above it (%s to %s m flown, GSD %s to %s "
        "cm/px), %zu waypoint%s added, %s frame\n",
        fixed_text(t.ground_min_m, 1).c_str(), fixed_text(t.ground_max_m, 1).c_str(),
        fixed_text(t.height_above_ground_m, 1).c_str(), fixed_text(t.agl_min_m, 1).c_str(),
        fixed_text(t.agl_max_m, 1).c_str(), fixed_text(t.gsd_min_m * 100, 3).c_str(),
        fixed_text(t.gsd_max_m * 100, 3).c_str(), t.waypoints_added,
        t.waypoints_added == 1 ? "" : "s", planning::frame_name(t.frame));
  }
  for (const planning::DronePlan& d : plan.drones) {
    const planning::DroneMission& m = d.mission;
    std::printf("  %-10s %s (work %s, transit %s), %s at %s m/s, %zu waypoints, %zu photos\n",
                d.name.c_str(), kilometres(m.path_length_m).c_str(),
                kilometres(m.work_length_m).c_str(), kilometres(m.transit_length_m).c_str(),
                planning::duration_text(m.flight_time_s).c_str(),
                fixed_text(d.speed_m_s, 1).c_str(), m.waypoint_count, d.photos.size());
    if (plan.drones.size() > 1)
      std::printf("    at %s m above home, launched %s after the first\n",
                  fixed_text(plan.imaging.altitude_m + d.layer_m, 1).c_str(),
                  planning::duration_text(d.launch_offset_s).c_str());
    for (const planning::Sortie& s : d.sorties) {
      std::printf("    sortie %d  %s, %s work, %zu photos, resumes at %s m, %s m", s.number,
                  planning::duration_text(s.mission.flight_time_s).c_str(),
                  kilometres(s.mission.work_length_m).c_str(), s.photos.size(),
                  fixed_text(s.resume.x, 1).c_str(), fixed_text(s.resume.y, 1).c_str());
      // Several drones' sorties are staggered at home (deconflict): each has its launch time.
      if (plan.drones.size() > 1)
        std::printf(", launched %s after the first",
                    planning::duration_text(s.launch_offset_s).c_str());
      std::printf("\n");
    }
  }
  std::printf(
      "  coverage   %s %% of the area; outside it: %s %% of the swath, %s m of lines, %s m of "
      "transit\n",
      fixed_text(plan.coverage.covered_fraction * 100, 3).c_str(),
      fixed_text(plan.coverage.outside_fraction * 100, 1).c_str(),
      fixed_text(plan.coverage.line_length_outside_m, 1).c_str(),
      fixed_text(plan.transit_outside_m, 1).c_str());
  if (plan.clearance.no_fly_m)
    std::printf("  clearance  %s m kept from %zu no-fly zone(s) (asked %s m)\n",
                fixed_text(*plan.clearance.no_fly_m, 1).c_str(), plan.no_fly.size(),
                fixed_text(plan.request.clearance_m, 1).c_str());
  std::string names;
  for (const auto& f : files) names += " " + f.first;
  std::printf("  wrote     %s\n", names.c_str());
  std::vector<std::string> warnings = plan.warnings;
  warnings.insert(warnings.end(), energy_warnings_.begin(), energy_warnings_.end());
  warnings.insert(warnings.end(), export_warnings_.begin(), export_warnings_.end());
  for (const std::string& w : warnings) std::cerr << "swath plan: warning: " << w << '\n';
}

preflight::CheckOptions PlanCommand::check_options(const planning::SurveyPlan& plan) const {
  preflight::CheckOptions options;
  // The area's holes and the zones as the user gave them (not as grown or simplified for the
  // fences), named as the planner's messages name them. The photo check's area is what the lines
  // cross (the flown area, --repair's pieces), not the file's ring: a repaired area's lines are
  // planned over pieces the file's ring does not describe, a hull's over ground outside it.
  const std::size_t holes = plan.request.field.polygon.holes.size();
  for (std::size_t k = 0; k < plan.no_fly_geo.size(); ++k)
    options.zones.push_back(
        {k < holes ? "hole " + std::to_string(k + 1) + " of " + field_  // as swath verify's
                   : planning::no_fly_name(plan, k),
         plan.no_fly_geo[k]});
  options.area = planning::lined_area(plan);
  options.clearance_m = plan.request.clearance_m;
  options.ceiling_m = ceiling_m_;
  if (plan.request.terrain) options.ground = plan.request.terrain->ground;
  return options;
}

int PlanCommand::run() {
  base::heap_on_huge_pages();
  if (!config_.empty())
    apply_mission_config(
        *app_, base::read_text_file(config_, "mission config", base::kMaxConfigFileBytes), config_);
  if (field_.empty()) throw InputError("no area: give FIELD (or 'field:' in --config)");
  if (camera_.empty()) throw InputError("no camera: give --camera (see 'swath cameras')");
  if (output_.empty()) throw InputError("no output directory: give -o DIR");
  check_numbers();
  planning::SurveyRequest asked = request();
  const planning::SurveyPlan plan = [&] {
    // The bar ends its line before the summary is printed.
    ProgressBar bar(progress_, "planning");
    asked.progress = [&bar](double fraction) { bar.update(fraction); };
    return planning::plan_survey(asked);
  }();
  const auto set = files(plan);
  verify_before_writing(set, check_options(plan));
  base::write_files_atomically(output_, set, "plan", /*keep_unlisted=*/true);
  report(plan, set);
  return base::kExitSuccess;
}

}  // namespace swath::apps
