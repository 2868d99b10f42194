#pragma once
// swath-fleet's applications (paper 000 §5; docs/swath-fleet.md): the case studies written as the
// paper writes them (hotspot, multiplexing, road, static, tracking, wifi), each for its world
// kind (swath::worlds), and the registry of a program's own apps. swath::fleet_apps sits above
// fleet and worlds: apps are written against the runtime's Ctx and read their worlds' sensors.

#include <string>
#include <vector>

#include "swath/fleet/leg.hpp"
#include "swath/fleet/runtime.hpp"
#include "swath/worlds/worlds.hpp"

namespace swath::fleet {

/// The built-in applications (hotspot, multiplexing, road, static, tracking, wifi), each for its
/// world kind (app_world_kind).
std::vector<App> builtin_apps();
/// An application of a program's own (out of tree: it links swath::fleet_apps and swath-fleet's
/// commands and calls apps::fleet_main), beside the built-in ones for the rest of the process: it
/// runs in worlds of `world_kind` (hotspot, road, rf_field, sites, static, tracking). Throws
/// std::invalid_argument when the name is empty or taken, or the kind unknown. `replace`: the
/// name may be a built-in app's, and this app runs instead of it (a Python file that implements
/// a built-in app logs under its name, so their runs and histories are interchangeable).
void register_app(App app, const std::string& world_kind, bool replace = false);
/// The built-in applications, then the registered ones.
std::vector<App> all_apps();
/// The world kind an app runs in ("multiplexing" → "sites", "wifi" → "rf_field", a registered
/// app's own, else its name).
std::string app_world_kind(const std::string& app);

/// Case 4's lower bound: the fastest order of the multiplexing app's segments for one drone from
/// `home` flying as `k` (rest to rest per leg, service times added), by brute force over every
/// order that keeps A before F, B and E anywhere, C then D with nothing between. Seconds.
double multiplexing_optimum_s(const worlds::SitesWorld& w, const Vec3& home, const Kinematics& k,
                              double altitude_m);

}  // namespace swath::fleet
