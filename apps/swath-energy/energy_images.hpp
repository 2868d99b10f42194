#pragma once
// The energy tool's pictures: the flight over the plan (trajectory.png) and the power, state of
// charge and parameters over time (energy.png).

#include <vector>

#include "map_furniture.hpp"
#include "swath/energy/plan.hpp"
#include "swath/energy/sim_config.hpp"
#include "swath/energy/simulation.hpp"
#include "swath/render/chart.hpp"
#include "swath/render/image.hpp"

namespace swath::apps {

struct TrajectoryImage {
  render::Scene scene;
  render::View view;
  ScaleBar scale_bar;
};

/// The planned path (grey), the simulated flight coloured by state of charge (green full, red at
/// the reserve), the triggering points (black triangles), the wind arrow, a scale bar, north.
TrajectoryImage trajectory_image(const energy::SimulationResult& result,
                                 const energy::SimConfig& config, int width_px, int height_px);

/// The colour of the flight at a state of charge.
render::Color soc_color(double soc, const energy::Battery& battery);

struct EnergyImage {
  render::Scene scene;
  render::View view;                        ///< the whole picture (charts use pixels only)
  std::vector<render::ChartLayout> charts;  ///< power, SoC, parameters; y offsets in `offsets_px`
  std::vector<double> offsets_px;
};

/// Three charts stacked: measured and model power (W); state of charge with the reserve line;
/// each parameter's level in its first-stage bounds (0 lowest, 1 highest) over time.
EnergyImage energy_image(const energy::SimulationResult& result, const energy::Plan& plan,
                         const energy::SimConfig& config, int width_px, int height_px);

}  // namespace swath::apps
