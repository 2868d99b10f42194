// fleet::DroneSpec holds a vehicle::Drone and only what swath-fleet's flights add beside it
// (docs/architecture.md: one concept, one type). The headers are read as text, so a second copy of
// a drone's field (its name, a cruise, climb or descent speed, a stored Kinematics) fails here
// whatever its type, and a field added to vehicle::Drone later is checked too.

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "swath/fleet/runtime.hpp"

namespace swath::fleet::drone_spec_check {

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The body of `struct NAME {` ... its closing brace, without // comments; "" when absent.
std::string struct_body(const std::string& code, const std::string& name) {
  const std::string uncommented = std::regex_replace(code, std::regex("//[^\n]*"), "");
  const std::size_t at = uncommented.find("struct " + name + " {");
  if (at == std::string::npos) return "";
  const std::size_t open = uncommented.find('{', at);
  int depth = 0;
  for (std::size_t i = open; i < uncommented.size(); ++i) {
    if (uncommented[i] == '{') ++depth;
    if (uncommented[i] == '}' && --depth == 0) return uncommented.substr(open + 1, i - open - 1);
  }
  return "";
}

// The data members a struct body declares: each top-level `TYPE NAME [= ...|{...}];`, where the
// part before any initializer has no parenthesis (that would be a function).
std::set<std::string> data_members(const std::string& body) {
  std::set<std::string> names;
  std::string statement;
  int depth = 0;
  for (const char c : body) {
    if (c == '{' || c == '(') ++depth;
    if (c == '}' || c == ')') --depth;
    if (c != ';' || depth != 0) {
      statement += c;
      continue;
    }
    const std::string declarator = statement.substr(0, statement.find_first_of("={"));
    std::smatch m;
    if (declarator.find('(') == std::string::npos &&
        std::regex_search(declarator, m, std::regex(R"(([A-Za-z_]\w*)\s*$)")))
      names.insert(m[1]);
    statement.clear();
  }
  return names;
}

// DroneSpec's members that copy what vehicle::Drone describes: vehicle::Drone's own member names,
// and the speeds and name under Kinematics' names or as a stored Kinematics.
std::set<std::string> copies(const std::set<std::string>& spec,
                             const std::set<std::string>& drone) {
  std::set<std::string> forbidden = drone;
  forbidden.insert({"name", "cruise_m_s", "climb_m_s", "descent_m_s", "accel_m_s2", "kinematics"});
  std::set<std::string> out;
  for (const std::string& m : spec)
    if (forbidden.count(m)) out.insert(m);
  return out;
}

std::set<std::string> members_of(const std::string& header, const std::string& name) {
  return data_members(struct_body(text_of(std::string(SWATH_SOURCE_DIR) + "/" + header), name));
}

TEST(DroneSpecCheck, ReadsTheMembersOfBothStructs) {
  // The check must see the structs it compares, or it would pass on nothing.
  const std::set<std::string> drone =
      members_of("vehicle/include/swath/vehicle/drone.hpp", "Drone");
  for (const char* m : {"name", "speed_m_s", "climb_speed_m_s", "descent_speed_m_s", "accel_m_s2"})
    EXPECT_TRUE(drone.count(m)) << m;
  const std::set<std::string> spec =
      members_of("fleet/include/swath/fleet/runtime.hpp", "DroneSpec");
  for (const char* m : {"drone", "home_m", "battery", "max_flight_time_s", "vehicle"})
    EXPECT_TRUE(spec.count(m)) << m;
  EXPECT_FALSE(spec.count("kinematics")) << "kinematics() is a function, not a member";
}

TEST(DroneSpecCheck, DroneSpecHoldsNoCopyOfTheDrone) {
  const std::set<std::string> found =
      copies(members_of("fleet/include/swath/fleet/runtime.hpp", "DroneSpec"),
             members_of("vehicle/include/swath/vehicle/drone.hpp", "Drone"));
  std::string names;
  for (const std::string& m : found) names += " " + m;
  EXPECT_TRUE(found.empty()) << "fleet::DroneSpec copies vehicle::Drone's" << names
                             << ": read them from DroneSpec::drone";
}

TEST(DroneSpecCheck, APlantedCopyIsNamed) {
  // The struct as it was before it held a vehicle::Drone, and a copy under the drone's own name.
  const std::string planted = R"(
    struct DroneSpec {
      std::string name;  // its name
      Vec3 home_m;
      Kinematics kinematics;
      double speed_m_s = 10;
      std::optional<VehicleAddress> vehicle;
      Kinematics flying() const;
    };)";
  const std::set<std::string> drone =
      members_of("vehicle/include/swath/vehicle/drone.hpp", "Drone");
  EXPECT_EQ(copies(data_members(struct_body(planted, "DroneSpec")), drone),
            (std::set<std::string>{"kinematics", "name", "speed_m_s"}));
}

// A DroneSpec nobody set flies Kinematics' defaults (not the planner's vehicle::Drone ones), and
// every Kinematics field follows the member it is computed from.
TEST(DroneSpecCheck, KinematicsComeFromTheDroneAndTheApproachRule) {
  const Kinematics defaults;
  const Kinematics k = DroneSpec{}.kinematics();
  EXPECT_EQ(k.cruise_m_s, defaults.cruise_m_s);
  EXPECT_EQ(k.approach_m_s, defaults.approach_m_s);
  EXPECT_EQ(k.approach_within_m, defaults.approach_within_m);
  EXPECT_EQ(k.accel_m_s2, defaults.accel_m_s2);
  EXPECT_EQ(k.climb_m_s, defaults.climb_m_s);
  EXPECT_EQ(k.descent_m_s, defaults.descent_m_s);
  DroneSpec d;
  d.drone.speed_m_s = 7, d.drone.climb_speed_m_s = 1.25, d.drone.descent_speed_m_s = 0.75;
  d.drone.accel_m_s2 = 0.5, d.approach_m_s = 1.5, d.approach_within_m = 4;
  const Kinematics set = d.kinematics();
  EXPECT_EQ(set.cruise_m_s, 7);
  EXPECT_EQ(set.climb_m_s, 1.25);
  EXPECT_EQ(set.descent_m_s, 0.75);
  EXPECT_EQ(set.accel_m_s2, 0.5);
  EXPECT_EQ(set.approach_m_s, 1.5);
  EXPECT_EQ(set.approach_within_m, 4);
  d.drone.speed_m_s.reset();  // a drone without a cruise speed flies the default one
  EXPECT_EQ(d.kinematics().cruise_m_s, defaults.cruise_m_s);
}

}  // namespace swath::fleet::drone_spec_check
