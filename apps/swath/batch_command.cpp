#include "batch_command.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "batch_workers.hpp"
#include "plan_command.hpp"
#include "shell_text.hpp"
#include "swath/base/csv_text.hpp"
#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/output_set.hpp"
#include "swath/base/parallel.hpp"
#include "swath/base/utf8.hpp"
#include "swath/geometry/field.hpp"

namespace swath::apps {

using base::InputError;
using json = nlohmann::ordered_json;
namespace fs = std::filesystem;

namespace {

// An area to plan: the file, its position in it, its name and the sub-directory it gets.
struct Job {
  std::string file, name, dir;
  std::size_t index = 0;
  bool single = false;  ///< the file holds only this area: no --feature
  /// A feature that is no area (no geometry, a point, an open line): why, for its row; it has no
  /// `swath plan` and no directory.
  std::string not_an_area;
};

// A directory name from an area's name: letters, digits, '-', '_' and '.' kept, the rest '_'.
std::string directory_name(const std::string& name) {
  std::string out;
  for (unsigned char c : name)
    out += std::isalnum(c) || c == '-' || c == '_' || c == '.' ? static_cast<char>(c) : '_';
  if (out.empty() || out == "." || out == "..") out = "area";
  if (out[0] == '.') out[0] = '_';  // never hidden, never the batch's manifest
  return out.substr(0, 80);
}

// `text` in lower case (ASCII).
std::string lowered(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

bool area_file(const fs::path& p) {
  const std::string ext = lowered(p.extension().string());
  for (const char* e : {".geojson", ".json", ".kml", ".csv", ".shp", ".zip", ".gpkg", ".kmz",
                        ".gpx", ".fgb", ".gml", ".wkt"})
    if (ext == e) return true;
  return false;
}

}  // namespace

void BatchCommand::setup(CLI::App& app) {
  app.add_option("AREAS", areas_,
                 "A file of several areas (GeoPackage, Shapefile, GeoJSON FeatureCollection, "
                 "KML, ...) or a directory of area files")
      ->required();
  app.add_option("-o,--output", output_,
                 "Directory for one sub-directory per area, batch.csv and batch.geojson")
      ->required();
  app.add_option("--layer", layer_, "The layer holding the areas (files with several layers)");
  app.add_option("--name-field", name_field_,
                 "The attribute that names areas and their sub-directories (default: name, "
                 "Name, NAME or id; else their position)");
  app.add_option("--jobs", jobs_,
                 "Areas planned at once (worker processes); the files do not depend on it")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  app.add_flag("--emit-jobs", emit_jobs_,
               "Print one `swath plan` command line per area instead (for GNU parallel or a "
               "Slurm array) and plan nothing");
  app.add_option("--timeout-s", timeout_s_,
                 "Seconds (wall clock) an area may plan before its worker is ended and the area "
                 "failed, its row saying so (0: no limit)")
      ->check(CLI::Range(0.0, 1e7))
      ->capture_default_str();
  app.add_flag("--progress", progress_, "Show a progress bar (only on a terminal)");
  app.allow_extras();
  app.footer(
      "Every other option goes to `swath plan` for each area, e.g. swath batch farm.gpkg "
      "-o out --camera sony-ilce-qx1 --altitude 60 --jobs 2.");
  app.callback([this, &app] { plan_args_ = app.remaining(); });
}

namespace {

// The plan options are parsed once, as `swath plan` would: a typo is refused before any area is
// planned (and before anything is written).
void check_plan_options(const std::vector<std::string>& plan_args, const std::string& areas,
                        const std::string& output) {
  for (const std::string& a : plan_args)
    if (a == "-o" || a == "--output" || a.rfind("--output=", 0) == 0 || a == "--feature" ||
        a == "--layer" || a == "--name-field")
      throw InputError(a + " is the batch's own (each area gets its own directory)");
  PlanCommand check;
  CLI::App app{"swath plan"};
  check.setup(app);
  std::vector<std::string> args{"-o", (fs::path(output) / "x").string(), areas};
  args.insert(args.end(), plan_args.begin(), plan_args.end());
  std::reverse(args.begin(), args.end());  // CLI11 parses a reversed vector
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    throw InputError("the plan options: " + std::string(e.what()));
  }
  check.check_options();  // the camera, the numbers, the files they name: as each plan would
}

// Whether `inner` is `outer` or lies inside it (both existing or not; symbolic links resolved).
bool same_or_inside(const fs::path& inner, const fs::path& outer) {
  std::error_code ec;
  const fs::path in = fs::weakly_canonical(fs::absolute(inner), ec);
  const fs::path out = fs::weakly_canonical(fs::absolute(outer), ec);
  if (ec) return false;
  auto i = in.begin();
  for (auto o = out.begin(); o != out.end(); ++o, ++i)
    if (o->empty())
      break;  // a trailing separator
    else if (i == in.end() || *i != *o)
      return false;
  return true;
}

// The output directory, refused before anything is planned: a file in its way (-o afile,
// -o afile/sub), or inside the directory of areas, where the next batch would list its batch.csv
// and batch.geojson as areas.
void check_output_directory(const std::string& output, const std::string& areas) {
  std::error_code ec;
  for (fs::path at = fs::absolute(output); !at.empty(); at = at.parent_path()) {
    if (fs::exists(at, ec) && !fs::is_directory(at, ec))
      throw InputError(output + ": cannot create the output directory (" +
                       (at == fs::absolute(output) ? std::string("a file of that name")
                                                   : at.string() + ", a file,") +
                       " is in the way)");
    if (fs::exists(at, ec) || at == at.parent_path()) break;
  }
  if (fs::is_directory(areas, ec) && same_or_inside(output, areas))
    throw InputError(output + ": the output directory is inside the directory of areas " + areas +
                     " (a next batch would plan its files as areas); give -o outside it");
}

// The output directory created (a system's refusal, /proc/nope, is bad input as for swath plan).
void create_output_directory(const std::string& output) {
  std::error_code ec;
  fs::create_directories(output, ec);
  if (ec || !fs::is_directory(output))
    throw InputError(output + ": cannot create the output directory (" +
                     (ec ? ec.message() : std::string("a file of that name is in the way")) + ")");
}

// Whether `object`'s members GeoJSON reads are spelled as GeoJSON spells them: GDAL's reader takes
// "Type" or "FEATURES" as its own (its member names ignore case), swath's does not.
bool exact_names(const nlohmann::json& object) {
  if (!object.is_object()) return true;
  for (const auto& [key, value] : object.items()) {
    const std::string lower = lowered(key);
    if (lower != key &&
        (lower == "type" || lower == "features" || lower == "geometry" || lower == "coordinates"))
      return false;
  }
  return true;
}

// Whether `file`, one of a directory's area files, is a GeoJSON of one polygon: a Polygon, a
// Feature of one, or a FeatureCollection of exactly one such Feature, read strictly (a key given
// twice, or one GDAL would take for another in other case, refused) and of at most 8 MiB (one
// polygon of swath's most vertices is far less; a larger file goes to GDAL, not into a second
// tree). GDAL lists at most one area for it (a feature gives more only as a MultiPolygon of
// several parts), and list_jobs() makes the same job of a directory's file that lists one area and
// of one GDAL cannot list: so its job is known without GDAL's listing (which was most of a batch's
// start: 0.3 s of CPU for 200 traced fields, before the first plan began).
bool one_polygon_geojson(const fs::path& file) {
  const std::string ext = lowered(file.extension().string());
  if (ext != ".geojson" && ext != ".json") return false;
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec || size > (std::uintmax_t{8} << 20)) return false;
  const auto type_of = [](const nlohmann::json* j) {
    const nlohmann::json* type = j ? base::json_find(*j, "type") : nullptr;
    return type && type->is_string() ? type->get<std::string>() : std::string();
  };
  try {
    const nlohmann::json root =
        base::parse_json_document(base::read_text_file(file, "area file"), file.string());
    const nlohmann::json* feature = &root;
    if (!exact_names(root)) return false;
    if (type_of(&root) == "FeatureCollection") {
      const nlohmann::json* features = base::json_find(root, "features");
      if (!features || !features->is_array() || features->size() != 1) return false;
      feature = &features->front();
      if (type_of(feature) != "Feature" || !exact_names(*feature)) return false;
    }
    const nlohmann::json* geometry =
        type_of(feature) == "Feature" ? base::json_find(*feature, "geometry") : feature;
    return geometry && exact_names(*geometry) && type_of(geometry) == "Polygon";
  } catch (const std::exception&) {
    return false;  // GDAL's listing says what it makes of it
  }
}

// Whether an area's directory `dir` under `output` may be written: not the batch's own files, not
// a name another area has, and not the area path or a directory holding it (an area "fields" of
// -o anc2 into anc2/fields, the directory of areas itself, left its plan there as areas for the
// next batch).
bool free_directory(const std::string& dir, const std::set<std::string>& used,
                    const std::string& output, const std::string& areas) {
  return !used.count(dir) && !same_or_inside(areas, fs::path(output) / dir);
}

// Every area of the file (or of each area file in the directory, by name), each with its own
// sub-directory under `output`.
std::vector<Job> list_jobs(const std::string& areas, const std::string& output,
                           const geometry::FieldReadOptions& options) {
  std::vector<Job> jobs;
  const bool directory = fs::is_directory(areas);
  // The first GIS file is listed by GDAL whatever it holds: GDAL is then loaded, and the jobs
  // that need it (a GeoJSON naming a CRS, --layer, --coverage-tif, ...) find it loaded in the
  // workers forked from this process, not loaded again by each.
  bool gdal_loaded = false;
  auto add_file = [&](const fs::path& file) {
    if (directory && gdal_loaded && one_polygon_geojson(file)) {
      jobs.push_back({file.string(), file.stem().string(), "", 0, true, {}});
      return;
    }
    std::vector<geometry::AreaEntry> found;
    const std::string ext = lowered(file.extension().string());
    gdal_loaded = gdal_loaded || (ext != ".csv" && ext != ".txt" && ext != ".wkt");
    try {
      found = geometry::list_areas(file, options);
    } catch (const std::exception&) {
      // One bad file of a directory is its own row: its `swath plan` says why, exit 2 (the
      // batch's exit 3); the other files are planned. A file given alone is refused with the
      // sentence its `swath plan` would give where it has one of its own (an empty file: "the
      // file is empty", not GDAL's "cannot open it as a vector file"), else the listing's.
      if (!directory) {
        geometry::read_field(file, options);
        throw;
      }
      jobs.push_back({file.string(), file.stem().string(), "", 0, true, {}});
      return;
    }
    const auto areas = static_cast<std::size_t>(std::count_if(
        found.begin(), found.end(), [](const auto& a) { return a.not_an_area.empty(); }));
    for (const auto& a : found)
      jobs.push_back({file.string(),
                      areas == 1 && a.not_an_area.empty() && file.extension() != ".gpkg"
                          ? file.stem().string()
                          : a.name,
                      "", a.index, areas == 1, a.not_an_area});
  };
  if (directory) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(areas)) {
      // An entry that cannot be looked at (a symlink loop, a dangling link) is a row too: its
      // `swath plan` says why.
      std::error_code ec;
      const bool regular = e.is_regular_file(ec);
      if ((regular || ec) && area_file(e.path())) files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    if (files.empty()) throw InputError(areas + ": no area files in this directory");
    for (const fs::path& f : files) add_file(f);
  } else {
    // A missing file is said so as swath plan says it, before its extension is looked at.
    if (!fs::is_regular_file(areas)) (void)base::read_text_file(areas, "area file");
    add_file(areas);
  }
  std::set<std::string> used = {"batch.csv", "batch.geojson"};  // the batch's own files
  for (Job& j : jobs) {
    if (!j.not_an_area.empty()) continue;  // no directory
    std::string dir = directory_name(j.name);
    for (int k = 2; !free_directory(dir, used, output, areas); ++k)
      dir = directory_name(j.name) + "-" + std::to_string(k);
    used.insert(dir);
    j.dir = dir;
  }
  return jobs;
}

// The area's outline as the plan read it, as a GeoJSON polygon (null for one it could not read).
json outline_geojson(const Job& j, geometry::FieldReadOptions options) {
  try {
    if (!j.single) options.feature = std::to_string(j.index);
    const geometry::Field f = geometry::read_field(j.file, options);
    json rings = json::array();
    for (const auto& ring : f.geo_rings) {
      json r = json::array();
      for (const auto& g : ring) r.push_back({g.lon_deg, g.lat_deg});
      if (!ring.empty()) r.push_back({ring.front().lon_deg, ring.front().lat_deg});
      rings.push_back(r);
    }
    return {{"type", "Polygon"}, {"coordinates", rings}};
  } catch (const std::exception&) {  // its row says why
    return nullptr;
  }
}

// batch.csv and batch.geojson from each area's summary.json, in the areas' order.
struct BatchTables {
  std::string csv, geojson;
  int failed = 0;
};
BatchTables batch_tables(const std::vector<Job>& jobs, const std::vector<PlanResult>& results,
                         const std::string& output, const geometry::FieldReadOptions& options) {
  BatchTables t;
  t.csv =
      "area,file,index,directory,status,exit_code,area_m2,lines,photos,path_length_m,"
      "flight_time_s,drones,message\n";
  json features = json::array();
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const Job& j = jobs[i];
    const PlanResult& r = results[i];
    const bool ok = r.exit_code == 0;
    t.failed += !ok;
    // Names and messages are bytes from the user's files: valid UTF-8 before JSON and CSV.
    const std::string name = base::valid_utf8(j.name), message = base::valid_utf8(r.message);
    const bool area = j.not_an_area.empty();  // a feature that is no area has no index
    json props{{"area", name},
               {"file", base::valid_utf8(j.file)},
               {"index", area ? json(j.index) : json(nullptr)},
               {"directory", j.dir},
               {"status", batch_status(r)},
               {"exit_code", r.exit_code}};
    std::string numbers = ",,,,,";
    if (ok) {
      const json s =
          json::parse(base::read_text_file(fs::path(output) / j.dir / "summary.json", "summary"));
      double lines = 0, photos = 0, length = 0, time = 0;
      for (const auto& d : s["drones"]) {
        lines += d.value("lines", 0.0);
        photos += d.value("photos", 0.0);
        length += d.value("path_length_m", 0.0);
        time = std::max(time, d.value("flight_time_s", 0.0));
      }
      const double area_m2 = s["area"].value("area_m2", 0.0);
      numbers = base::fixed_text(area_m2, 3) + "," + base::fixed_text(lines, 0) + "," +
                base::fixed_text(photos, 0) + "," + base::fixed_text(length, 3) + "," +
                base::fixed_text(time, 3) + "," + std::to_string(s["drones"].size());
      // batch.csv's columns, in its order; counts as integers.
      props["area_m2"] = area_m2;
      props["lines"] = static_cast<std::int64_t>(std::llround(lines));
      props["photos"] = static_cast<std::int64_t>(std::llround(photos));
      props["path_length_m"] = length;
      props["flight_time_s"] = time;
      props["drones"] = s["drones"].size();
    } else {
      props["message"] = message;
    }
    // The directory as it is named on disk: directory_name() keeps only letters, digits, '-',
    // '_' and '.', which carry no formula a spreadsheet could run (a function needs brackets),
    // so it takes no apostrophe.
    t.csv += csv_field(name) + "," + csv_field(base::valid_utf8(j.file)) + "," +
             (area ? std::to_string(j.index) : "") + "," + j.dir + "," + batch_status(r) + "," +
             std::to_string(r.exit_code) + "," + numbers + "," + csv_field(ok ? "" : message) +
             "\n";
    features.push_back(json{{"type", "Feature"},
                            {"properties", props},
                            {"geometry", area ? outline_geojson(j, options) : json(nullptr)}});
  }
  t.geojson = json{{"type", "FeatureCollection"}, {"features", features}}.dump(1) + "\n";
  return t;
}

// A file swath wrote, whole ("" where there is none or it cannot be read).
std::string read_small_file(const fs::path& path) {
  try {
    return base::read_text_file(path, "file");
  } catch (const std::exception&) {
    return {};
  }
}

// The area directories the batch before wrote into `output`: its batch.csv's `directory` column,
// where the batch's manifest lists batch.csv (swath wrote it; a user's file of that name is not
// read).
std::set<std::string> earlier_directories(const fs::path& output) {
  const std::string manifest = read_small_file(output / ".swath-batch.files");
  if (manifest.find("\nbatch.csv\n") == std::string::npos) return {};
  const std::string text = read_small_file(output / "batch.csv");
  // Messages may hold line breaks and names '#': records as swath wrote them, no comments.
  base::CsvText csv(text, "batch.csv", base::CsvText::Records::quoted_breaks);
  std::set<std::string> dirs;
  try {
    if (!csv.next() || csv.cells().size() < 4 || csv.cells()[3] != "directory") return dirs;
    while (csv.next())
      if (csv.cells().size() > 3 && !csv.cells()[3].empty()) dirs.insert(csv.cells()[3]);
  } catch (const InputError&) {  // a batch.csv edited out of shape: the rows before it
  }
  return dirs;
}

// Whether `name` is a temporary or kept old file a plan ended by SIGKILL leaves (OutputSet's
// `.NAME.tmp-` or `.NAME.old-` and 16 hex digits).
bool plan_leftover(const std::string& name) {
  constexpr std::size_t kTail = 5 + 16;
  if (name.size() <= 1 + kTail || name[0] != '.') return false;
  const std::string tail = name.substr(name.size() - kTail);
  return (tail.starts_with(".tmp-") || tail.starts_with(".old-")) &&
         std::all_of(tail.begin() + 5, tail.end(), [](char c) {
           return std::isdigit(static_cast<unsigned char>(c)) || (c >= 'a' && c <= 'f');
         });
}

// An area directory of this batch or the one before whose area this batch did not plan: the
// plan swath wrote there (the files its .swath-plan.files lists, the manifest, a killed plan's
// temporaries) removed, and the directory once empty, so that no row's failure sits beside a
// complete plan (an older one, or one a timed-out worker finished as it was ended). Anything
// else in it is the user's and stays. A name that is not a plain directory (a symbolic link) is
// left alone.
void remove_plan_directory(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(fs::symlink_status(dir, ec))) return;
  std::istringstream manifest(read_small_file(dir / ".swath-plan.files"));
  for (std::string name; std::getline(manifest, name);)
    if (!name.empty() && name[0] != '#' && name.find('/') == std::string::npos && name != "." &&
        name != "..")
      fs::remove(dir / name, ec);
  fs::remove(dir / ".swath-plan.files", ec);
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (plan_leftover(e.path().filename().string())) fs::remove(e.path(), ec);
  fs::remove(dir, ec);  // only when empty
}

// The `swath plan` command line of one area.
std::vector<std::string> command_line(const Job& j, const std::string& layer,
                                      const std::vector<std::string>& plan_args,
                                      const std::string& output) {
  std::vector<std::string> argv{own_program_path("swath"), "plan", j.file};
  if (!j.single) argv.insert(argv.end(), {"--feature", std::to_string(j.index)});
  if (!layer.empty()) argv.insert(argv.end(), {"--layer", layer});
  argv.insert(argv.end(), plan_args.begin(), plan_args.end());
  argv.insert(argv.end(), {"-o", (fs::path(output) / j.dir).string()});
  return argv;
}

// Each area's result: a feature that is no area refused by its own sentence, the others planned
// by the workers.
std::vector<PlanResult> plan_jobs(const std::vector<Job>& jobs,
                                  const std::vector<std::vector<std::string>>& commands,
                                  int parallel, bool progress, double timeout_s) {
  std::vector<std::vector<std::string>> planned;
  for (std::size_t i = 0; i < jobs.size(); ++i)
    if (jobs[i].not_an_area.empty()) planned.push_back(commands[i]);
  const std::vector<PlanResult> answers = plan_in_workers(planned, parallel, progress, timeout_s);
  std::vector<PlanResult> results;
  std::size_t next = 0;
  for (const Job& j : jobs)
    results.push_back(j.not_an_area.empty() ? answers[next++]
                                            : PlanResult{base::kExitBadInput, j.not_an_area});
  return results;
}

// The area directories of the batch before that this one has not planned into, and those of its
// own areas that failed: each plan removed (remove_plan_directory()).
void remove_unplanned(const fs::path& output, std::set<std::string> earlier,
                      const std::vector<Job>& jobs, const std::vector<PlanResult>& results) {
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (jobs[i].dir.empty()) continue;
    if (results[i].exit_code == base::kExitSuccess && !results[i].timed_out)
      earlier.erase(jobs[i].dir);
    else
      earlier.insert(jobs[i].dir);
  }
  for (const std::string& dir : earlier)
    if (directory_name(dir) == dir) remove_plan_directory(output / dir);  // never ../ or a path
}

}  // namespace

int BatchCommand::run() {
  check_plan_options(plan_args_, areas_, output_);
  check_output_directory(output_, areas_);
  geometry::FieldReadOptions options;
  if (!layer_.empty()) options.layer = layer_;
  if (!name_field_.empty()) options.name_field = name_field_;
  const std::vector<Job> jobs = list_jobs(areas_, output_, options);
  std::vector<std::vector<std::string>> commands;
  for (const Job& j : jobs) commands.push_back(command_line(j, layer_, plan_args_, output_));
  if (emit_jobs_) {
    std::string lines, warnings;  // all of them before any is printed: a refused name prints none
    for (std::size_t i = 0; i < jobs.size(); ++i) {
      if (!jobs[i].not_an_area.empty()) {  // no command line plans it
        warnings += "swath batch: warning: " + jobs[i].not_an_area + "\n";
        continue;
      }
      const auto& argv = commands[i];
      std::string line;
      for (const std::string& a : argv) line += (line.empty() ? "" : " ") + shell_word(a);
      lines += line + "\n";
    }
    std::cout << lines;
    std::cerr << warnings;
    if (timeout_s_ > 0)
      std::cerr << "swath batch: warning: --timeout-s does not reach the command lines printed; "
                   "give the engine's own limit (e.g. GNU parallel's --timeout)\n";
    return base::kExitSuccess;
  }
  // Each worker's plans take their share of the machine's threads: two plans of two threads each
  // on two cores ran the 200 traced outlines in 9.8-11.1 s, of one thread each in 8.5-9.0 s.
  const bool threads_given = std::any_of(
      plan_args_.begin(), plan_args_.end(),
      [](const std::string& a) { return a == "--threads" || a.starts_with("--threads="); });
  if (!threads_given)
    for (std::vector<std::string>& argv : commands)
      argv.insert(
          argv.end(),
          {"--threads", std::to_string(std::max(1u, base::machine_threads() / unsigned(jobs_)))});
  // The user's batch.csv refused before any area is planned into the directory, not after.
  base::check_output_names(output_, "batch", {"batch.csv", "batch.geojson"});
  create_output_directory(output_);
  const std::set<std::string> earlier = earlier_directories(output_);
  const std::vector<PlanResult> results = plan_jobs(jobs, commands, jobs_, progress_, timeout_s_);
  const BatchTables tables = batch_tables(jobs, results, output_, options);
  base::OutputSet set(output_, "batch", {base::OutputSet::Mode::amend, 10.0});
  remove_unplanned(output_, earlier, jobs, results);  // under the batch's lock
  set.add("batch.csv", tables.csv);
  set.add("batch.geojson", tables.geojson);
  set.commit();
  std::cout << jobs.size() - static_cast<std::size_t>(tables.failed) << " of " << jobs.size()
            << " areas planned into " << output_
            << (tables.failed ? "; see batch.csv for the others" : "") << "\n";
  return tables.failed ? base::kExitPartial : base::kExitSuccess;
}

}  // namespace swath::apps
