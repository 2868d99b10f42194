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

void RenderCommand::write_html(const std::filesystem::path& dir, const std::string& page) const {
  base::OutputSet set(dir, "plan", {base::OutputSet::Mode::amend, 10.0});
  set.add("plan.html", page);
  set.commit();
  std::cout << "swath render: wrote " << (dir / "plan.html").string() << '\n';
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
  const std::string page = html_ ? html_page(dir) : "";
  if (html_ && coverage_.empty() && paths_.empty()) {
    write_html(dir, page);
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
  const std::filesystem::path coverage =
      coverage_.empty() ? dir / "coverage.png" : std::filesystem::path(coverage_);
  std::vector<std::pair<std::filesystem::path, std::string>> out{
      {coverage, render::encode_png(render::draw(image.scene, image.view))}};
  if (!paths_.empty()) {
    image.scene.strips.clear();
    out.push_back({paths_, render::encode_png(render::draw(image.scene, image.view))});
  }
  if (html_) write_html(dir, page);
  for (const auto& [path, png] : out) {
    // Into the plan's own directory the picture joins the plan's set (a re-plan replaces it);
    // anywhere else it is a set of its own, never a plan's.
    const std::filesystem::path parent = path.has_parent_path() ? path.parent_path() : ".";
    std::error_code ec;
    const bool plan_directory = std::filesystem::equivalent(parent, dir, ec);
    base::OutputSet set(parent, plan_directory ? "plan" : "render",
                        {base::OutputSet::Mode::amend, 10.0});
    set.add(path.filename().string(), png);
    set.commit();
    std::cout << "swath render: wrote " << path.string() << '\n';
  }
  return base::kExitSuccess;
}

}  // namespace swath::apps
