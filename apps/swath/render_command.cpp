#include "render_command.hpp"

#include <filesystem>
#include <iostream>

#include "basemap.hpp"
#include "coverage_image.hpp"
#include "plan_html.hpp"
#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/output_set.hpp"
#include "swath/planning/plan_features.hpp"

namespace swath::apps {
namespace {

std::string read(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw base::InputError(path.string() + ": cannot open (is this a swath plan directory?)");
  return base::read_text_file(path, "swath plan file");
}

// A file render writes: the page or a picture, and whether the user named it.
struct RenderedFile {
  std::filesystem::path path;
  std::string content;
  bool named = false;    ///< by --coverage or --paths: replaces what is there, as asked
  const char* remedy{};  ///< else what to do about a file of the user's in its place
};

// Into the plan's own directory a file joins the plan's set (a re-plan replaces it); anywhere
// else it is a set of its own, never a plan's. A name render chose itself never replaces a file
// no manifest lists (the user's own coverage.png).
struct Placement {
  std::filesystem::path directory;
  std::string kind;
  base::OutputSet::Options options;
};

Placement placement(const RenderedFile& file, const std::filesystem::path& plan) {
  const std::filesystem::path parent = file.path.has_parent_path() ? file.path.parent_path() : ".";
  std::error_code ec;
  const bool plan_directory = std::filesystem::equivalent(parent, plan, ec);
  base::OutputSet::Options options{base::OutputSet::Mode::amend, 10.0, !file.named};
  if (file.remedy != nullptr) options.unlisted_remedy = file.remedy;
  return {parent, plan_directory ? "plan" : "render", options};
}

// Every file checked before any is written: a refused picture leaves no page behind either.
void write(const std::vector<RenderedFile>& files, const std::filesystem::path& dir) {
  for (const RenderedFile& file : files) {
    const Placement where = placement(file, dir);
    base::check_output_names(where.directory, where.kind, {file.path.filename().string()},
                             where.options);
  }
  for (const RenderedFile& file : files) {
    const Placement where = placement(file, dir);
    base::OutputSet set(where.directory, where.kind, where.options);
    set.add(file.path.filename().string(), file.content);
    set.commit();
    std::cout << "swath render: wrote " << file.path.string() << '\n';
  }
}

}  // namespace

std::string RenderCommand::html_page(const std::filesystem::path& dir) const {
  // Read and check the plan first, as the pictures do: a directory that is no plan gets no page.
  planning::parse_mission_geojson(read(dir / "mission.geojson"),
                                  (dir / "mission.geojson").string());
  planning::parse_plan_figures(read(dir / "summary.json"), (dir / "summary.json").string());
  const auto lookup = [&dir](const std::string& name) -> std::optional<std::string> {
    std::error_code ec;
    if (!std::filesystem::exists(dir / name, ec)) return std::nullopt;
    return base::read_text_file(dir / name, "swath plan file");
  };
  return plan_html(lookup, dir_, basemap_url_, basemap_);
}

void RenderCommand::setup(CLI::App& app) {
  app.add_option("DIR", dir_, "A directory written by swath plan")->required();
  app.add_option("--coverage", coverage_, "Coverage picture to write (default DIR/coverage.png)");
  app.add_option("--paths", paths_, "Also a picture of the flight paths only, without footprints");
  app.add_option("--size", size_, "Picture size, WxH pixels")->capture_default_str();
  app.add_flag("--html", html_,
               "Write DIR/plan.html, the plan on a map (one self-contained page), instead of "
               "coverage.png (which --coverage still asks for)");
  app.add_option("--basemap-url", basemap_url_,
                 "plan.html: XYZ tile template drawn behind the plan "
                 "(http(s)://host/{z}/{x}/{y}.png; the page then fetches these tiles)");
  app.add_option("--basemap", basemap_,
                 "A raster drawn behind the plan in the pictures and plan.html (an orthophoto: "
                 "GeoTIFF or any raster GDAL reads, any CRS; reprojected, read from disk only)");
}

int RenderCommand::run() {
  const std::filesystem::path dir(dir_);
  if (!basemap_url_.empty() && !html_)
    throw base::InputError("--basemap-url draws behind plan.html: give --html too");
  // Everything made before anything is written: a refused basemap leaves no page behind.
  std::vector<RenderedFile> files;
  if (html_) files.push_back({dir / "plan.html", html_page(dir), false, "move it"});
  if (html_ && coverage_.empty() && paths_.empty()) {
    write(files, dir);
    return base::kExitSuccess;
  }
  const auto [w, h] = parse_size(size_);
  // In this order: a directory that is no plan is named by its mission.geojson first.
  const planning::PlanFeatures features = planning::parse_mission_geojson(
      read(dir / "mission.geojson"), (dir / "mission.geojson").string());
  const planning::PlanFigures figures =
      planning::parse_plan_figures(read(dir / "summary.json"), (dir / "summary.json").string());
  CoverageImage image = coverage_image(features, figures, w, h);
  if (!basemap_.empty()) put_basemap_under(image, basemap_);
  files.push_back({coverage_.empty() ? dir / "coverage.png" : std::filesystem::path(coverage_),
                   render::encode_png(render::draw(image.scene, image.view)), !coverage_.empty(),
                   "move it, or give --coverage another file"});
  if (!paths_.empty()) {
    image.scene.strips.clear();
    files.push_back({paths_, render::encode_png(render::draw(image.scene, image.view)), true});
  }
  write(files, dir);
  return base::kExitSuccess;
}

}  // namespace swath::apps
