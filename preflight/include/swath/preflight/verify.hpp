#pragma once
// Preflight checks of written mission files (issue 45): no mission leaves swath unless an
// independent check of the files themselves passes. Each file is flown as the autopilot flies it
// (flown_path.hpp) and checked against no-fly zones, its fences, a ceiling and the ground, the
// battery, the other drones, and where its camera triggers.

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "swath/energy/sim_config.hpp"
#include "swath/geometry/ground.hpp"
#include "swath/missions/mission.hpp"
#include "swath/preflight/flown_path.hpp"

namespace swath::preflight {

/// A no-fly zone as the user gave it.
struct Zone {
  std::string name;  ///< "pond.geojson", "hole 1 of meadow.geojson"
  std::vector<geometry::GeoPoint> ring;
};

struct CheckOptions {
  std::vector<Zone> zones;
  double clearance_m = 5.0;  ///< from `zones` (the file's own exclusion fences: not entered)
  /// The surveyed area's outer rings, if known: a leg with the camera on that never meets them is
  /// a transit.
  std::vector<std::vector<geometry::GeoPoint>> area;
  double ceiling_m = 120.0;  ///< above the ground (with `ground`) or above home
  /// least height above the ground along cruise legs (with `ground`)
  double min_height_m = geometry::kLeastHeightAboveGround_m;
  double separation_m = 10.0;  ///< least 3-D distance between two drones at the same time
  std::shared_ptr<const geometry::Ground> ground;
  std::optional<energy::DroneProfile> drone;
  /// ArduPilot files' inclusion fences as a union (FENCE_OPTIONS bit 2 set): inside one of them
  /// is inside. Otherwise (ArduPilot's default, and PX4 always) the vehicle must stay inside every
  /// one.
  bool fence_union = false;
  FlightModel model;
};

/// One drone's mission file and when it launches.
struct DroneFile {
  missions::Mission mission;
  double launch_offset_s = 0.0;
  /// Sorties of one drone share a name here: they fly one after another (each launched at its
  /// own offset or when the one before lands, whichever is later), never against each other.
  /// Empty: a drone alone.
  std::string sorties_of;
  /// Flies in place of another drone's file (a twin of its .plan, or a part of its split Litchi
  /// twin): checked as a flight of its own, and for separation as its drone against the other
  /// drones' files at its own times (a split Litchi flight's trips home and back between parts
  /// make it longer than its .plan); its photos are not counted again.
  bool instead = false;
  /// The drone that flies the file: files of one drone are never checked against each other
  /// (one drone flies one at a time). Empty: sorties_of, else the file itself.
  std::string drone = {};
  /// Its place among its drone's sorties (from 1; summary.json's order): it flies after those
  /// before it where their launch offsets tie. 0: not a sortie.
  std::size_t sortie = 0;
};

/// A check that failed somewhere.
struct Violation {
  std::string check;  ///< "no-fly zone", "fence", "ceiling", "ground", "energy", "separation",
                      ///< "photos", "agreement"
  std::string place;  ///< file and item ("drone-1.plan: item 7")
  std::optional<geometry::GeoPoint> at;
  double amount = 0.0;  ///< by how much (unit in `text`)
  std::string text;     ///< the whole sentence
};

/// A check's figure, or why it could not run.
struct Figure {
  std::string check;
  bool ran = true;
  std::optional<double> value;  ///< the check's figure (least clearance, max height, ...)
  std::string text;
};

struct Report {
  std::vector<std::string> files;
  std::vector<Figure> figures;
  std::vector<Violation> violations;
  /// What does not fail a check but the pilot must know (a fence ArduPilot cannot store).
  std::vector<std::string> warnings;
  bool ok() const { return violations.empty(); }
};

/// Checks the drones' files together (separation across them; every other check per file).
/// Throws base::InputError for a file the model cannot fly (an AMSL item without a home altitude,
/// a command it does not model: fly()).
Report verify(const std::vector<DroneFile>& drones, const CheckOptions& options);

/// Checks a set of written files by name and content (a plan directory, or `swath plan`'s output
/// before it is written): each NAME.plan is a drone (NAME.waypoints, NAME-litchi.csv,
/// NAME-survey.plan and NAME.kmz are its twins, which must agree with it; the parts
/// NAME-litchi-1.csv, -2, ... of a split Litchi flight must agree joined; every twin and part is
/// also flown and checked in the .plan's place, within its fences, a Litchi or DJI file from its
/// home, the parts in turn as sorties); without .plan files, the .waypoints,
/// -litchi.csv, -litchi-N.csv (in turn, from part 1's first row) or .kmz files are the drones. A
/// .waypoints file of fence and rally items only (missions::is_wpl_fence_file, whatever its name)
/// adds to every drone's fences, summary.json's drones[].launch_offset_s sets launch times and
/// drones[].sorties[].file names the files one drone flies in turn. Other files are ignored.
/// Throws base::InputError naming the file for one that cannot be read.
Report verify_files(const std::vector<std::pair<std::string, std::string>>& files,
                    const CheckOptions& options);

/// The report as printed lines (one per check, one per violation) and as one JSON object.
std::string report_text(const Report& report);
std::string report_json(const Report& report);

}  // namespace swath::preflight
