// `swath plan` with drones of a fleet file's batteries or --endurance: no flight longer than the
// charge a drone takes off with less the reserve, sorties sized to it, the refusal that says so.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace swath::test {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// A fleet file at the meadow's home of drones at 5 m/s, each (name, battery_level, endurance_s,
// its own home where `own_home`: three-quads' charlie's), written into `dir`; its path.
struct BatteryDrone {
  std::string name;
  double level, endurance_s;
  bool own_home = false;
};

std::string battery_fleet(const std::string& dir, const std::vector<BatteryDrone>& drones) {
  fs::create_directories(dir);
  const std::string path = dir + "/fleet.yaml";
  std::ofstream file(path);
  file << "home: {lat: 47.3965, lon: 8.5405, alt: 0}\ndrones:\n";
  for (const BatteryDrone& d : drones)
    file << "  - {name: " << d.name << ", battery_level: " << d.level
         << ", endurance_s: " << d.endurance_s << ", speed_m_s: 5"
         << (d.own_home ? ", home: {lat: 47.3982, lon: 8.5468}}\n" : "}\n");
  return path;
}

// Every flight of each drone as summary.json gives it (its sorties in order, or its one flight).
std::map<std::string, std::vector<double>> flight_times(const json& summary) {
  std::map<std::string, std::vector<double>> out;
  for (const json& d : summary["drones"]) {
    std::vector<double>& times = out[d["name"].get<std::string>()];
    if (d.contains("sorties") && d["sorties"].is_array() && !d["sorties"].empty()) {
      for (const json& s : d["sorties"]) times.push_back(s["flight_time_s"].get<double>());
    } else {
      times.push_back(d["flight_time_s"].get<double>());
    }
  }
  return out;
}

const std::string kMeadow40 =
    "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 40 ";

TEST(PlanCli, RegionDivisionKeepsEveryFlightWithinItsCharge) {
  // weak: 0.35 x 1200 s = 420 s of charge, 336 s less the 20 % reserve, 2100 m of range, which
  // count no climb, stop or descent: its band by capability took 459 s.
  const std::string dir = fresh_dir("charge-region");
  const std::string fleet = battery_fleet(dir, {{"full", 1.0, 1800}, {"weak", 0.35, 1200}});
  for (const std::string balance : {"makespan", "capability"}) {
    const std::string out = dir + "/" + balance;
    const CliRun run = run_swath(kMeadow40 + "--fleet " + fleet + " --division region --balance " +
                                 balance + " -o " + out);
    ASSERT_EQ(run.exit_code, 0) << balance << ": " << run.err;
    auto times = flight_times(json::parse(read_text(out + "/summary.json")));
    ASSERT_EQ(times["full"].size(), 1u);
    EXPECT_LE(times["full"][0], 1440.0) << balance;
    EXPECT_LE(times["weak"][0], 336.0) << balance;
    EXPECT_GT(times["weak"][0], 0.0) << balance;
    EXPECT_EQ(run.err.find("swath plan: warning: shares in proportion to the capabilities would "
                           "fly a drone beyond its range or charge") != std::string::npos,
              balance == "capability")
        << run.err;
    // summary.json says how the shares were cut: by makespan either way, the capability asked
    // for re-cut (it said "capability" over shares that were not in proportion).
    const json division = json::parse(read_text(out + "/summary.json"))["division"];
    EXPECT_EQ(division["balance"], "makespan") << balance;
    EXPECT_EQ(division.contains("balance_asked"), balance == "capability") << division.dump();
    if (balance == "capability") EXPECT_EQ(division["balance_asked"], "capability");
  }
}

TEST(PlanCli, AFlightLongerThanItsChargeIsRefusedNamingTheFleetFile) {
  // One drone of 0.5 x 1200 s, 480 s less the reserve: the meadow at 40 m takes 23 min; no
  // division can re-cut it.
  const std::string dir = fresh_dir("charge-refused");
  const std::string fleet = battery_fleet(dir, {{"solo", 0.5, 1200}});
  for (const std::string balance : {"makespan", "capability"}) {
    const std::string out = dir + "/" + balance;
    const CliRun run = run_swath(kMeadow40 + "--fleet " + fleet + " --division region --balance " +
                                 balance + " -o " + out);
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_NE(run.err.find("swath plan: drone solo's flight takes 23 min"), std::string::npos)
        << run.err;
    EXPECT_NE(run.err.find(", longer than the 8 min 00 s its battery gives less the 20 % reserve "
                           "(battery_level 0.5 x endurance_s 1200 in " +
                           fleet +
                           ", --reserve 0.2); add drones or battery, cut the flights into sorties "
                           "with --sorties auto, or fly higher with a larger --altitude (fewer "
                           "lines)\n"),
              std::string::npos)
        << run.err;
    // Not the balance on flight time: both balances have cut on it (where capability shares were
    // too long); it was advised with --balance makespan given.
    EXPECT_EQ(run.err.find("--balance"), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  }
}

TEST(PlanCli, AFlightIntoTheReserveIsRefusedCountingTheBatteryLevel) {
  // 0.3 x 5000 s = 1500 s of charge, 1200 s less the 20 % reserve: the meadow's 23 min flight
  // lands on less than the reserve (against the 5000 s endurance it would not): refused, nothing
  // written; --reserve 0, the pilot's own word that the whole charge may be flown, plans it.
  const std::string dir = fresh_dir("charge-reserve");
  const std::string fleet = battery_fleet(dir, {{"part", 0.3, 5000}});
  const CliRun run = run_swath(kMeadow40 + "--fleet " + fleet + " -o " + dir + "/out");
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_FALSE(fs::exists(dir + "/out"));
  const CliRun whole =
      run_swath(kMeadow40 + "--fleet " + fleet + " --reserve 0 -o " + dir + "/whole");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const json s = json::parse(read_text(dir + "/whole/summary.json"));
  const double flight_s = s["drones"][0]["flight_time_s"].get<double>();
  ASSERT_GT(flight_s, 1200.0);
  ASSERT_LE(flight_s, 1500.0);
  EXPECT_EQ(run.err, "swath plan: drone part's flight takes " +
                         s["drones"][0]["flight_time"].get<std::string>() +
                         ", longer than the 20 min 00 s its battery gives less the 20 % reserve "
                         "(battery_level 0.3 x endurance_s 5000 in " +
                         fleet +
                         ", --reserve 0.2); add drones or battery, cut the flights into sorties "
                         "with --sorties auto, or fly higher with a larger --altitude (fewer "
                         "lines)\n");
}

TEST(PlanCli, AFlightLongerThanTheEnduranceLessTheReserveIsRefused) {
  // One drone, --endurance 1200: 960 s less the reserve, the meadow at 40 m flies 23 min 06 s.
  // Refused (exit 2, nothing written) naming the drone, its flight, its charge and the ways out;
  // 1800 s (1440 s less the reserve) flies it, unwarned.
  const std::string dir = fresh_dir("endurance-refused");
  const CliRun run = run_swath(kMeadow40 + "--endurance 1200 -o " + dir + "/out");
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_FALSE(fs::exists(dir + "/out"));
  EXPECT_EQ(run.err,
            "swath plan: drone drone-1's flight takes 23 min 06 s, longer than the 16 min 00 s "
            "its battery gives less the 20 % reserve (--endurance 1200, --reserve 0.2); add drones "
            "or battery, cut the flights into sorties with --sorties auto, or fly higher with a "
            "larger --altitude (fewer lines)\n");
  const CliRun fits = run_swath(kMeadow40 + "--endurance 1800 -o " + dir + "/fits");
  ASSERT_EQ(fits.exit_code, 0) << fits.err;
  EXPECT_EQ(fits.err.find("warning"), std::string::npos) << fits.err;
  const json s = json::parse(read_text(dir + "/fits/summary.json"));
  EXPECT_LE(s["drones"][0]["flight_time_s"].get<double>(), 1440.0);
  // With sorties the same battery flies it in sorties of 16 min at most.
  const CliRun sorties =
      run_swath(kMeadow40 + "--endurance 1200 --sorties auto -o " + dir + "/sorties");
  ASSERT_EQ(sorties.exit_code, 0) << sorties.err;
  const auto sortie_times = flight_times(json::parse(read_text(dir + "/sorties/summary.json")));
  ASSERT_GT(sortie_times.at("drone-1").size(), 1u);
  for (const double t : sortie_times.at("drone-1")) EXPECT_LE(t, 960.0 + 1e-6);
}

TEST(PlanCli, TheFirstSortieFitsTheChargeTheLaterOnesAFullBattery) {
  // low: 0.4 x 600 s; weak: 0.3 x 1200 s, short of its share in one battery (once refused "longer
  // than its range" under --sorties auto). Sortie 1 flies the charge less the 20 % reserve.
  const std::string dir = fresh_dir("charge-sorties");
  const std::vector<std::vector<BatteryDrone>> fleets{
      {{"full", 1.0, 600}, {"low", 0.4, 600, true}},
      {{"full", 1.0, 1200}, {"weak", 0.3, 1200, true}}};
  for (std::size_t f = 0; f < fleets.size(); ++f) {
    const std::string sub = dir + "/" + std::to_string(f);
    const std::string fleet = battery_fleet(sub, fleets[f]);
    const CliRun run =
        run_swath(kMeadow40 + "--fleet " + fleet + " --sorties auto -o " + sub + "/out");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    auto times = flight_times(json::parse(read_text(sub + "/out/summary.json")));
    for (const BatteryDrone& d : fleets[f]) {
      const std::vector<double>& t = times[d.name];
      ASSERT_FALSE(t.empty()) << d.name;
      EXPECT_LE(t[0], d.level * d.endurance_s * 0.8 + 1e-6) << d.name;
      for (std::size_t k = 1; k < t.size(); ++k)
        EXPECT_LE(t[k], d.endurance_s * 0.8 + 1e-6) << d.name << " sortie " << k + 1;
    }
    EXPECT_GT(times[fleets[f][1].name].size(), 1u) << "the low drone flies sorties";
  }
}

}  // namespace
}  // namespace swath::test
