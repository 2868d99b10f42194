// The farm-scale corpus (docs/performance.md): traced field outlines, as a cooperative or an agency
// would batch them, generated from a seed (tests/support/field_shapes.hpp, traced_outline) and
// written as one GeoJSON file each, placed in turn at six latitudes so that the local frame is
// exercised north and south, near the equator and at 60 N. scripts/bench-batch plans them.
//
//   swath_field_corpus -o DIR [--count N] [--seed S]
//
// Prints one line: how many outlines, their vertices (median, least, most), how many are concave
// and how many have holes.

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "field_shapes.hpp"
#include "swath/geometry/classification.hpp"
#include "swath/geometry/local_frame.hpp"

namespace {

namespace geo = swath::geometry;

struct Place {
  double lat_deg, lon_deg;
};
// Switzerland, New South Wales, southern Norway, Uganda (0.3 N), Nebraska, Tanzania (2 S).
constexpr Place kPlaces[] = {{47.0, 8.0}, {-34.0, 150.8}, {60.0, 10.5},
                             {0.3, 32.6}, {41.0, -98.0},  {-2.0, 33.0}};

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9f", x);  // the C locale: this program never sets one
  return text;
}

std::string geojson(const std::string& name, const geo::Polygon& area, Place place) {
  const geo::LocalFrame frame({place.lat_deg, place.lon_deg, 0.0});
  std::string out = R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":)"
                    R"({"name":")" +
                    name + R"("},"geometry":{"type":"Polygon","coordinates":[)";
  for (std::size_t r = 0; r < geo::ring_count(area); ++r) {
    const geo::Ring& ring = geo::ring_at(area, r);
    out += r ? ",[" : "[";
    for (std::size_t i = 0; i <= ring.size(); ++i) {  // GeoJSON rings are closed
      const geo::GeoPoint g = frame.to_geo(ring[i % ring.size()]);
      out += (i ? ",[" : "[") + number(g.lon_deg) + "," + number(g.lat_deg) + "]";
    }
    out += "]";
  }
  return out + "]}}]}\n";
}

bool parse_count(const std::string& text, long long lo, long long hi, long long& value) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size() && value >= lo && value <= hi;
}

int refuse(const std::string& sentence) {
  std::fprintf(stderr, "swath_field_corpus: %s\n", sentence.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  long long count = 200, seed = 52;
  std::string dir;
  for (int i = 1; i < argc; i += 2) {
    const std::string flag = argv[i];
    if (i + 1 >= argc)
      return refuse(flag + " needs a value (usage: -o DIR [--count N] [--seed S])");
    const std::string value = argv[i + 1];
    if (flag == "-o" || flag == "--output")
      dir = value;
    else if (flag == "--count") {
      if (!parse_count(value, 1, 100000, count))
        return refuse("--count " + value + ": not a whole number from 1 to 100000");
    } else if (flag == "--seed") {
      if (!parse_count(value, 0, 1LL << 62, seed))
        return refuse("--seed " + value + ": not a whole number from 0");
    } else {
      return refuse("unknown flag " + flag + " (usage: -o DIR [--count N] [--seed S])");
    }
  }
  if (dir.empty()) return refuse("no output directory (usage: -o DIR [--count N] [--seed S])");

  // All outlines first, then the files: nothing is written if generation fails.
  swath::test::Rng rng(static_cast<std::uint64_t>(seed) * 1000003 + 52);
  std::vector<geo::Polygon> areas;
  for (long long i = 0; i < count; ++i) areas.push_back(swath::test::traced_outline(rng));

  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return refuse(dir + ": cannot create the directory (" + ec.message() + ")");
  std::vector<std::size_t> vertices;
  int concave = 0, holed = 0;
  for (std::size_t i = 0; i < areas.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "traced-%03zu", i);
    const std::string path = dir + "/" + name + ".geojson";
    std::ofstream out(path, std::ios::binary);
    out << geojson(name, areas[i], kPlaces[i % std::size(kPlaces)]);
    if (!out.flush()) return refuse(path + ": cannot write the file");
    std::size_t n = 0;
    for (std::size_t r = 0; r < geo::ring_count(areas[i]); ++r)
      n += geo::ring_at(areas[i], r).size();
    vertices.push_back(n);
    concave += geo::classify(areas[i]).type == geo::AreaType::concave;
    holed += !areas[i].holes.empty();
  }
  std::sort(vertices.begin(), vertices.end());
  std::printf("%zu outlines in %s: %zu vertices median (%zu-%zu), %d concave, %d with holes\n",
              areas.size(), dir.c_str(), vertices[vertices.size() / 2], vertices.front(),
              vertices.back(), concave, holed);
  return 0;
}
