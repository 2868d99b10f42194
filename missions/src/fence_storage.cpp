// ArduPilot's fence storage, counted as AC_PolyFence_loader counts it (fence_storage.hpp).
#include "swath/missions/fence_storage.hpp"

#include <algorithm>

namespace swath::missions {
namespace {

constexpr std::size_t kHeaderBytes = 4;       // the storage's format magic
constexpr std::size_t kPolygonBytes = 1 + 1;  // type, vertex count
constexpr std::size_t kPointBytes = 4 + 4;    // lat, lon (1e-7 degrees)
constexpr std::size_t kCircleBytes = 1 + 12;  // type; lat, lon, radius

bool same_circle(const FenceCircle& a, const FenceCircle& b) {
  return a.centre.lat_deg == b.centre.lat_deg && a.centre.lon_deg == b.centre.lon_deg &&
         a.radius_m == b.radius_m;
}

std::size_t count_new_circles(const std::vector<FenceCircle>& circles,
                              std::vector<FenceCircle>& seen) {
  std::size_t added = 0;
  for (const FenceCircle& c : circles) {
    if (std::any_of(seen.begin(), seen.end(), [&](const auto& s) { return same_circle(s, c); }))
      continue;
    seen.push_back(c);
    ++added;
  }
  return added;
}

std::string counted(std::size_t n, const char* noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

}  // namespace

FenceStorage ardupilot_fence_storage(const std::vector<std::size_t>& polygon_points,
                                     std::size_t circles) {
  FenceStorage s;
  s.polygons = polygon_points.size();
  s.circles = circles;
  for (const std::size_t n : polygon_points) s.points += n;
  s.bytes =
      kHeaderBytes + s.polygons * kPolygonBytes + s.points * kPointBytes + s.circles * kCircleBytes;
  return s;
}

std::vector<std::vector<geometry::GeoPoint>> distinct_rings(
    const std::vector<std::vector<geometry::GeoPoint>>& rings) {
  std::vector<std::vector<geometry::GeoPoint>> out;
  auto same = [](const geometry::GeoPoint& p, const geometry::GeoPoint& q) {
    return p.lat_deg == q.lat_deg && p.lon_deg == q.lon_deg;
  };
  for (const auto& ring : rings)
    if (std::none_of(out.begin(), out.end(), [&](const auto& o) {
          return std::equal(o.begin(), o.end(), ring.begin(), ring.end(), same);
        }))
      out.push_back(ring);
  return out;
}

FenceStorage ardupilot_fence_storage(const Mission& mission) {
  std::vector<std::vector<geometry::GeoPoint>> rings = mission.inclusion_fences;
  rings.insert(rings.end(), mission.exclusion_fences.begin(), mission.exclusion_fences.end());
  std::vector<std::size_t> points;
  for (const auto& ring : distinct_rings(rings)) points.push_back(ring.size());
  std::vector<FenceCircle> circles;
  std::size_t n_circles = count_new_circles(mission.inclusion_circles, circles);
  n_circles += count_new_circles(mission.exclusion_circles, circles);
  return ardupilot_fence_storage(points, n_circles);
}

std::string px4_fence_warning(const FenceStorage& storage) {
  const std::size_t items = storage.points + storage.circles;
  if (items <= kPx4FenceItems) return {};
  std::string what =
      counted(storage.points, "point") + " in " + counted(storage.polygons, "polygon");
  if (storage.circles > 0) what += " and " + counted(storage.circles, "circle");
  return "the fence has " + what + ": " + std::to_string(items) + " fence items, more than the " +
         std::to_string(kPx4FenceItems) +
         " PX4 takes in all (every polygon's vertices and circles together); PX4 refuses the "
         "upload and keeps its old fence; give fewer or simpler no-fly zones";
}

std::string fence_storage_warning(const FenceStorage& storage, bool fixed_wing) {
  const std::size_t limit = fixed_wing ? kArduPlaneFenceBytes : kArduCopterFenceBytes;
  if (storage.bytes <= limit) return {};
  // The most points one polygon alone can have within the limit.
  const std::size_t one_polygon = (limit - kHeaderBytes - kPolygonBytes) / kPointBytes;
  std::string what =
      counted(storage.points, "point") + " in " + counted(storage.polygons, "polygon");
  if (storage.circles > 0) what += " and " + counted(storage.circles, "circle");
  return "the fence has " + what + ": " + std::to_string(storage.bytes) +
         " bytes of ArduPilot's fence storage, more than the " + std::to_string(limit) + " bytes " +
         (fixed_wing ? "ArduPlane" : "ArduCopter") +
         " keeps on a flight controller (one polygon of at most " + std::to_string(one_polygon) +
         " points); ArduPilot refuses the upload and keeps its old fence; give fewer or simpler "
         "no-fly zones (or fence space on the SD card: BRD_SD_FENCE)";
}

}  // namespace swath::missions
