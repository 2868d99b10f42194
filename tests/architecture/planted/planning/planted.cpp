// Violations planted for tests/architecture (never compiled): each line the check must name.
#include <string>

namespace swath::planning {

bool is_waypoint(int cmd) {
  return cmd == 16;  // planted: a compared command
}

int kind_of(int command) {
  switch (command) {
    case 22:  // planted: a case of a switch on a command
      return 1;
    default:
      return 0;
  }
}

int mav_command(bool land) {
  return land ? 21 : 20;  // planted: returned by a function that names a command
}

std::string json_item() {
  return R"({"command": 178, "params": []})";  // planted: a JSON command
}

std::string fence_row() {
  return wpl_row(0, 0, 0, 5001, {});  // planted: a WPL row's command
}

// Not commands: numbers elsewhere, and commands named in comments ("command": 16).
int not_commands(int seeds, int commands_sent) {
  int command = 0;
  const int limit = 1000;
  return seeds > 16 ? limit : command + commands_sent;
}

int too_long() {
  int n = 0;
  ++n;
  ++n;
  ++n;
  ++n;
  ++n;
  ++n;
  ++n;
  ++n;
  ++n;
  return n;
}

// Planted: a second fleet-file reader. One key in a JSON summary is not one.
double flight_time_s(const YAML::Node& drone) {
  return drone["endurance_s"].as<double>() * drone["battery_level"].as<double>();
}

// Planted: a second state-of-charge integrator.
double drained(double soc, double current_a, double dt_s, const Pack& pack) {
  return soc - current_a * dt_s / (3600.0 * pack.capacity_ah);
}

}  // namespace swath::planning
