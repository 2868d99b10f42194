#include "swath/fleet/simulated_fleet.hpp"

#include <algorithm>
#include <limits>

namespace swath::fleet {

SimulatedFleet::SimulatedFleet(const std::vector<DroneSpec>& drones, double layer_base_m,
                               double layer_step_m) {
  for (std::size_t i = 0; i < drones.size(); ++i) {
    Vehicle v;
    v.kinematics = drones[i].kinematics();
    v.home_m = drones[i].home_m;
    v.home_m.z = 0;
    v.layer_m = layer_base_m + layer_step_m * static_cast<double>(i);
    v.at_m = v.home_m;
    vehicles_.push_back(std::move(v));
  }
}

SimulatedFleet::Vehicle& SimulatedFleet::at(int drone) {
  return vehicles_.at(static_cast<std::size_t>(drone));
}
const SimulatedFleet::Vehicle& SimulatedFleet::at(int drone) const {
  return vehicles_.at(static_cast<std::size_t>(drone));
}

// On its leg until the leg's end, compared as the runtime compares it (start + duration), so
// that both see the same leg as finished.
bool SimulatedFleet::moving(const Vehicle& v, double t_s) {
  return v.leg && t_s < v.leg_start_s + v.leg->duration_s();
}

// A homing leg ends over home: the vehicle then descends there at its descent speed.
Leg SimulatedFleet::descent(const Vehicle& v) {
  const Vec3 top = v.leg->to();
  return Leg(top, {top.x, top.y, 0}, v.kinematics);
}

Vec3 SimulatedFleet::position(const Vehicle& v, double t_s) {
  if (!v.leg) return v.at_m;
  if (moving(v, t_s)) return v.leg->position_at(t_s - v.leg_start_s);
  if (!v.homing) return v.leg->to();
  return descent(v).position_at(t_s - v.leg_start_s - v.leg->duration_s());
}

void SimulatedFleet::fly(Vehicle& v, double t_s, const Vec3& to_m, bool homing) {
  const Vec3 from = position(v, t_s);
  const Leg* current = moving(v, t_s) ? &*v.leg : nullptr;
  v.leg = next_leg(current, t_s - v.leg_start_s, from, to_m, v.kinematics);
  v.leg_start_s = t_s;
  v.homing = homing;
}

void SimulatedFleet::go_to(int drone, double t_s, const Vec3& to_m, double, double, double) {
  fly(at(drone), t_s, to_m, false);
}

// Home at the altitude it flies at (from the ground: its layer), then down.
void SimulatedFleet::return_home(int drone, double t_s) {
  Vehicle& v = at(drone);
  const Vec3 here = position(v, t_s);
  fly(v, t_s, {v.home_m.x, v.home_m.y, here.z > 0 ? here.z : v.layer_m}, true);
}

void SimulatedFleet::hold(int drone, double t_s) {
  Vehicle& v = at(drone);
  v.at_m = position(v, t_s);
  v.leg.reset();
  v.homing = false;
}

// Down where it is, at the descent speed (the runtime's landing over home, or an abort's).
void SimulatedFleet::land(int drone, double t_s) {
  Vehicle& v = at(drone);
  const Vec3 here = position(v, t_s);
  fly(v, t_s, {here.x, here.y, 0}, true);
}

void SimulatedFleet::advance_to(double t_s) {
  now_s_ = std::max(now_s_, t_s);
}

VehicleReport SimulatedFleet::report(int drone) const {
  const Vehicle& v = at(drone);
  VehicleReport r;
  r.link_up = true;
  r.position_known = true;
  r.position_m = position(v, now_s_);
  const bool ended = v.leg && now_s_ >= arrival_s(drone);
  r.arrived = ended && !v.homing;
  r.landed_home = ended && v.homing;
  return r;
}

double SimulatedFleet::arrival_s(int drone) const {
  const Vehicle& v = at(drone);
  if (!v.leg) return std::numeric_limits<double>::infinity();
  const double end_s = v.leg_start_s + v.leg->duration_s();
  return v.homing ? end_s + descent(v).duration_s() : end_s;
}

}  // namespace swath::fleet
