#pragma once
// The simulated fleet (docs/swath-fleet.md) behind the runtime's Backend: each vehicle flies its
// DroneSpec's kinematics exactly, leg by leg in closed form (leg.hpp): to the target's altitude,
// then level with the approach rule and bounded accelerations; home: the same to above home,
// then down at the descent speed and landed (land: down where it is). It has no clock and no I/O of
// its own: a command starts a leg at the time it is given, and arrival_s() tells the runtime when
// each leg ends, so time jumps from event to event. Its links never drop by themselves (injected
// faults are the runtime's: docs/swath-fleet.md, 'Faults').

#include <optional>
#include <string>
#include <vector>

#include "swath/fleet/backend.hpp"
#include "swath/fleet/leg.hpp"
#include "swath/fleet/runtime.hpp"

namespace swath::fleet {

class SimulatedFleet final : public Backend {
 public:
  /// One vehicle per drone, starting landed at its home; drone i's layer (where a return starts
  /// from the ground) is layer_base_m + layer_step_m × i, m.
  SimulatedFleet(const std::vector<DroneSpec>& drones, double layer_base_m, double layer_step_m);

  int vehicles() const override { return static_cast<int>(vehicles_.size()); }
  /// The speeds given are the drone's kinematics, which the leg flies.
  void go_to(int drone, double t_s, const Vec3& to_m, double, double, double) override;
  void act(int, const std::string&, bool) override {}
  void return_home(int drone, double t_s) override;
  void hold(int drone, double t_s) override;
  void land(int drone, double t_s) override;
  void advance_to(double t_s) override;
  VehicleReport report(int drone) const override;
  void end_run() override {}
  double arrival_s(int drone) const override;
  bool reports_every_tick() const override { return false; }

 private:
  struct Vehicle {
    Kinematics kinematics;
    Vec3 home_m;  // z = 0
    double layer_m = 20;
    Vec3 at_m;  // where it is when not on a leg
    std::optional<Leg> leg;
    double leg_start_s = 0;
    bool homing = false;  // after the leg, down to the ground (descent())
  };
  Vehicle& at(int drone);
  const Vehicle& at(int drone) const;
  static bool moving(const Vehicle& v, double t_s);
  static Leg descent(const Vehicle& v);
  static Vec3 position(const Vehicle& v, double t_s);
  static void fly(Vehicle& v, double t_s, const Vec3& to_m, bool homing);

  std::vector<Vehicle> vehicles_;
  double now_s_ = 0;
};

}  // namespace swath::fleet
