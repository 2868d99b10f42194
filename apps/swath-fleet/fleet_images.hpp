#pragma once
// swath-fleet's pictures (docs/swath-fleet.md): tracks.png — the world (fence, road, source, sites,
// access points), each drone's track with direction arrows, where it sensed, where requests were
// cancelled, a scale bar and north; gantt.png — a row per drone over time: flying, acting,
// hovering, held for a task, returning, charging, lost or unreachable.

#include <string>

#include "swath/fleet/runtime.hpp"
#include "swath/render/image.hpp"
#include "swath/render/scene.hpp"
#include "swath/render/view.hpp"
#include "swath/worlds/worlds.hpp"

namespace swath::apps {

struct FleetPicture {
  render::Scene scene;
  render::View view;
};

/// The colour of each drone's track (cycled) and of each mode in the Gantt chart.
render::Color drone_color(std::size_t index);
render::Color mode_color(const std::string& mode);

FleetPicture tracks_picture(const worlds::BaseWorld& world, const fleet::RunRecord& record,
                            int width_px, int height_px);
/// Rows from y = 40 px, each (height − 80) / drones tall; time from x = 120 px to width − 30 px
/// over [0, record.end_s] (see gantt_x_px).
FleetPicture gantt_picture(const fleet::RunRecord& record, int width_px, int height_px);
double gantt_x_px(double t_s, double end_s, int width_px);
double gantt_row_centre_px(std::size_t drone, std::size_t drones, int height_px);

}  // namespace swath::apps
