// The split corpus table (issue 18, docs/swath-plan.md): split against hull over generated families
// of areas a pilot meets, with coverage by the tests' independent footprint oracle. Not a Google
// Benchmark: a quality table, printed as Markdown, with every row as CSV on request.
//
//   swath_split_corpus [--per-family N] [--seed S] [--csv FILE] [--write DIR]
//                      [--cells runs|boustrophedon|best] [--margin 0|half] [--altitude M]
//                      [--directions one|per-region]
//
// --write DIR puts every shape there as GeoJSON (placed at 47 N 8 E), to plan and draw with swath.

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "field_shapes.hpp"
#include "split_measure.hpp"
#include "swath/geometry/local_frame.hpp"

namespace {

struct Stats {
  std::vector<double> ratios;
  double worst_coverage = 1, worst_flyable = 1, outside_m = 0, ms = 0;
  int below = 0, convex = 0, per_region = 0;
};

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[std::min(v.size() - 1, std::size_t(q * double(v.size())))];
}

void print(const std::string& name, const Stats& s) {
  double mean = 0;
  for (double r : s.ratios) mean += r / double(s.ratios.size());
  std::printf(
      "| %s | %zu (+%d convex) | %.3f | %.3f | %.3f | %.3f | %.2f %% | %.2f %% | %d | %.1f m | "
      "%.0f ms |\n",
      name.c_str(), s.ratios.size(), s.convex, mean, quantile(s.ratios, 0.5),
      quantile(s.ratios, 0.9),
      s.ratios.empty() ? 0 : *std::max_element(s.ratios.begin(), s.ratios.end()),
      100 * s.worst_coverage, 100 * s.worst_flyable, s.below, s.outside_m,
      s.ms / double(std::max<std::size_t>(1, s.ratios.size())));
}

void write_geojson(const std::string& path, const swath::geometry::Polygon& area) {
  const swath::geometry::LocalFrame frame({47.0, 8.0, 0.0});
  std::ofstream out(path);
  out.precision(10);
  out << R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
      << R"("geometry":{"type":"Polygon","coordinates":[)";
  for (std::size_t r = 0; r < swath::geometry::ring_count(area); ++r) {
    const auto& ring = swath::geometry::ring_at(area, r);
    out << (r ? ",[" : "[");
    for (std::size_t i = 0; i <= ring.size(); ++i) {
      const swath::geometry::GeoPoint g = frame.to_geo(ring[i % ring.size()]);
      out << (i ? "," : "") << '[' << g.lon_deg << ',' << g.lat_deg << ']';
    }
    out << ']';
  }
  out << "]}}]}\n";
}

}  // namespace

int main(int argc, char** argv) {
  int per_family = 20;
  std::uint64_t seed = 1;
  std::string csv, write_dir;
  swath::test::SplitSettingsForCorpus settings;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--per-family")
      per_family = std::atoi(argv[i + 1]);
    else if (flag == "--seed")
      seed = std::strtoull(argv[i + 1], nullptr, 10);
    else if (flag == "--csv")
      csv = argv[i + 1];
    else if (flag == "--write")
      write_dir = argv[i + 1];
    else if (flag == "--altitude")
      settings.altitude_m = std::atof(argv[i + 1]);
    else if (flag == "--directions")
      settings.directions = std::string(argv[i + 1]) == "per-region"
                                ? swath::planning::SplitDirections::per_region
                                : swath::planning::SplitDirections::one;
    else if (flag == "--margin")
      settings.half_footprint_margin = std::string(argv[i + 1]) == "half";
    else if (flag == "--cells") {
      const std::string v = argv[i + 1];
      settings.cells = v == "runs"            ? swath::planning::SplitCells::runs
                       : v == "boustrophedon" ? swath::planning::SplitCells::boustrophedon
                                              : swath::planning::SplitCells::best;
    } else {
      std::fprintf(stderr, "swath_split_corpus: unknown flag %s\n", flag.c_str());
      return 2;
    }
  }
  if (!write_dir.empty()) std::filesystem::create_directories(write_dir);
  std::ofstream rows;
  if (!csv.empty()) {
    rows.open(csv);
    rows << "family,index,vertices,holes,concave,split_m,hull_m,ratio,coverage,flyable_coverage,"
            "reported_coverage,"
            "line_outside_m,transit_outside_m,cells,lines,regions,plan_ms\n";
  }
  std::map<std::string, Stats> families;
  Stats all;
  for (const swath::test::CorpusShape& shape : swath::test::split_corpus(seed, per_family)) {
    if (!write_dir.empty())
      write_geojson(write_dir + "/" + shape.family + "-" + std::to_string(shape.index) + ".geojson",
                    shape.area);
    swath::test::SplitRow r;
    try {
      r = swath::test::measure_split(shape.area, settings);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s %d: %s\n", shape.family.c_str(), shape.index, e.what());
      for (const auto& p : shape.area.outer) std::fprintf(stderr, "  %.3f %.3f\n", p.x, p.y);
      return 1;
    }
    if (rows.is_open())
      rows << shape.family << ',' << shape.index << ',' << shape.area.outer.size() << ','
           << shape.area.holes.size() << ',' << r.concave << ',' << r.split_m << ',' << r.hull_m
           << ',' << r.split_m / r.hull_m << ',' << r.coverage << ',' << r.flyable_coverage << ','
           << r.reported_coverage << ',' << r.line_outside_m << ',' << r.transit_outside_m << ','
           << r.cells << ',' << r.lines << ',' << r.regions << ',' << r.plan_ms << '\n';
    for (Stats* s : {&families[shape.family], &all}) {
      if (!r.concave) {
        ++s->convex;
        continue;
      }
      s->ratios.push_back(r.split_m / r.hull_m);
      s->per_region += r.regions > 0;
      s->worst_coverage = std::min(s->worst_coverage, r.coverage);
      s->worst_flyable = std::min(s->worst_flyable, r.flyable_coverage);
      s->below += r.coverage < 0.999;
      s->outside_m += r.line_outside_m + r.transit_outside_m;
      s->ms += r.plan_ms;
    }
  }
  std::printf(
      "| family | concave shapes | mean split/hull | median | p90 | worst | worst coverage | "
      "worst, flyable | < 99.9 %% | outside | plan |\n"
      "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& [name, s] : families) print(name, s);
  print("all", all);
  if (settings.directions == swath::planning::SplitDirections::per_region)
    std::printf("\nflown with a direction per region: %d of %zu concave shapes\n", all.per_region,
                all.ratios.size());
  return 0;
}
