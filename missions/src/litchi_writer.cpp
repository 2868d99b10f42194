// Litchi mission CSV writer (docs/swath-plan.md): Litchi's column set, one row per waypoint,
// missions above Litchi's largest split into parts that continue one another; read back by
// mission.cpp (parse_mission).
#include <algorithm>
#include <cmath>
#include <utility>

#include "swath/base/number_text.hpp"
#include "swath/missions/writers.hpp"

namespace swath::missions {
namespace {

using base::fixed_text;

// Litchi's column set as its Mission Hub exports and imports it (metric units).
std::string header() {
  std::string h =
      "latitude,longitude,altitude(m),heading(deg),curvesize(m),rotationdir,gimbalmode,"
      "gimbalpitchangle";
  for (int k = 1; k <= 15; ++k)
    h += ",actiontype" + std::to_string(k) + ",actionparam" + std::to_string(k);
  return h +
         ",altitudemode,speed(m/s),poi_latitude,poi_longitude,poi_altitude(m),poi_altitudemode,"
         "photo_timeinterval,photo_distinterval\n";
}

// Litchi's waypoint actions (DJI's waypoint action types): -1 none, 0 stay (ms), 1 take photo.
constexpr int kActionNone = -1, kActionStay = 0, kActionPhoto = 1;
constexpr int kMaxStay_ms = 32'000;  // DJI's limit on a stay action

// The turn towards the next point's heading: 0 clockwise, 1 counter-clockwise, the shorter way.
int rotation_dir(double from_deg, double to_deg) {
  const double turn = std::remainder(to_deg - from_deg, 360.0);
  return turn >= 0 ? 0 : 1;
}

struct Row {
  const ExportPoint* point;
  const ExportPoint* next;  ///< nullptr: the last point of its file
  bool resumed = false;     ///< the first point of a later part: its actions were done at the end
                            ///< of the part before
};

std::string row_text(const Row& row, const LitchiSettings& s) {
  const ExportPoint& p = *row.point;
  std::string out =
      fixed_text(p.geo.lat_deg, 9) + "," + fixed_text(p.geo.lon_deg, 9) + "," +
      fixed_text(p.altitude_m, 3) + "," + fixed_text(p.heading_deg, 2) + ",0," +
      std::to_string(row.next ? rotation_dir(p.heading_deg, row.next->heading_deg) : 0) + ",2," +
      fixed_text(s.gimbal_pitch_deg, 3);  // gimbal mode 2: interpolate
  std::vector<std::pair<int, int>> actions;
  if (p.hold_s > 0 && !row.resumed)
    actions.push_back(
        {kActionStay, std::min(kMaxStay_ms, static_cast<int>(std::lround(p.hold_s * 1000)))});
  if (p.shot && !row.resumed) actions.push_back({kActionPhoto, 0});
  for (std::size_t k = 0; k < 15; ++k) {
    const auto [type, param] = k < actions.size() ? actions[k] : std::pair{kActionNone, 0};
    out += ',';
    out += std::to_string(type);
    out += ',';
    out += std::to_string(param);
  }
  // altitudemode 0: above the take-off point, as every swath altitude is (frame 3); 1 would make
  // Litchi shift each waypoint by its own elevation model's ground height under it.
  out += ",0," + fixed_text(p.speed_m_s > 0 ? p.speed_m_s : s.speed_m_s, 3) + ",0,0,0,0,";
  // Photos on the legs the mission triggers on: the interval starts at the leg's first waypoint
  // (as DJI's waypoint missions read it, for the flight to the next waypoint); -1: none.
  const bool photos = p.photo_leg && row.next != nullptr;
  const double interval = s.trigger_value;
  out += (photos && s.trigger == TriggerMode::time ? fixed_text(interval, 3) : "-1") + ",";
  out += (photos && s.trigger == TriggerMode::distance ? fixed_text(interval, 3) : "-1") + "\n";
  return out;
}

}  // namespace

std::string write_litchi_part(const std::vector<ExportPoint>& points,
                              std::optional<std::size_t> resumed_row,
                              const LitchiSettings& settings) {
  std::string text = header();
  for (std::size_t i = 0; i < points.size(); ++i)
    text += row_text({&points[i], i + 1 < points.size() ? &points[i + 1] : nullptr,
                      resumed_row && i == *resumed_row},
                     settings);
  return text;
}

std::vector<std::string> write_litchi_csv(const std::vector<ExportPoint>& points,
                                          const LitchiSettings& settings) {
  std::vector<std::string> parts;
  // Parts of at most max_rows rows; each after the first starts at the point the one before
  // ended at, so that the pilot resumes where the last mission stopped. A part ends at the last
  // point it may end at (Litchi flies home from there and back out to it), else at its last row.
  std::size_t first = 0;
  while (true) {
    std::size_t end =
        first + std::min(points.size() - first, std::max<std::size_t>(settings.max_rows, 2));
    if (end < points.size() && settings.may_end_at)
      for (std::size_t last = end - 1; last > first; --last)
        if (settings.may_end_at(last)) {
          end = last + 1;
          break;
        }
    const std::vector<ExportPoint> part(points.begin() + first, points.begin() + end);
    parts.push_back(write_litchi_part(
        part, first > 0 ? std::optional<std::size_t>(0) : std::nullopt, settings));
    if (end >= points.size()) break;
    first = end - 1;
  }
  return parts;
}

}  // namespace swath::missions
