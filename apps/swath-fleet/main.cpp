// swath-fleet: applications written against virtual drones, run on a simulated fleet by a
// runtime that assigns drones to requests moment by moment (paper 000, BeeCluster).
#include "fleet_main.hpp"

int main(int argc, char** argv) {
  return swath::apps::fleet_main(argc, argv);
}
